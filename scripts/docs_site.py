#!/usr/bin/env python3
"""Builds the documentation site (MkDocs) from docs/ and the README, warnings as errors.

The pages are the files of docs/, as written for reading on the repository, with two changes:
docs/input-format.md (one long page) is split into one page per `## ` section, a component family
each, and every link is pointed at the page that now holds its anchor. Links into the repository
outside docs/ (../include/structmd.h) become plain text: the site has no copy of those files.

MkDocs then checks every link and every anchor (strict mode), so a link to a heading that does not
exist fails the build. Headings get GitHub's anchors (pymdownx's slugify), the ones the links were
written against.

usage: docs_site.py OUTPUT_DIR    (the pages go to OUTPUT_DIR/pages, the site to OUTPUT_DIR/site)
Exit status 77 when mkdocs or pymdown-extensions is not installed (pip install mkdocs pymdown-extensions "mkdocstrings[python]").
"""

import posixpath
import re
import shutil
import subprocess
import sys
from pathlib import Path
from typing import Dict, List, Tuple

SKIPPED = 77
REPOSITORY = Path(__file__).resolve().parents[1]
DOCS = REPOSITORY / "docs"
INPUT_FORMAT = "input-format.md"
# The sections of the input format's first page: the document's shape and its four plain sections.
INPUT_FORMAT_FIRST_PAGE_ENDS_AT = "## Neighbour lists"
# The other pages of the site, in the order of its navigation.
PAGES = [("C API", "c-api.md"), ("Python", "python.md"), ("Python API", "python-api.md"), ("Plugins", "plugins.md"),
         ("Architecture", "architecture.md"), ("Robustness", "robustness.md"), ("Benchmarks", "benchmarks.md")]
# The tutorials, each a page of docs/tutorials whose code blocks take the scripts of examples/tutorials
# (which their tests run) through pymdownx.snippets, so the code shown is the code tested.
TUTORIALS = [("A Lennard-Jones liquid", "tutorials/lj-liquid.md"),
             ("A coupling loop in C and Python", "tutorials/coupling-loop.md"),
             ("A polymer melt", "tutorials/polymer-melt.md"),
             ("A BDHI suspension", "tutorials/bdhi-suspension.md")]

HEADING = re.compile(r"^(#{1,6}) +(.+?) *$")
FENCE = re.compile(r"^ *(```|~~~)")
# [text](target), the text with at most one level of brackets (["NonBonded","LennardJones"]); targets
# without spaces or parentheses, which is all docs/ uses.
LINK = re.compile(r"\[((?:[^\[\]]|\[[^\]]*\])*)\]\(([^)\s]+)\)")
# Files of docs/ that are not pages of the site: links to them become text, like links out of docs/.
NOT_ON_SITE = ("Doxyfile",)


# The Python package's reference, rendered by mkdocstrings from its docstrings and annotations.
PYTHON_MODULES = ["structmd.simulation", "structmd.builder", "structmd.errors", "structmd.ase", "structmd.ipi", "structmd.dlpack",
                  "structmd.plot"]
PYTHON_API_PAGE = "# Python API\n\nThe package `structmd`, from its docstrings ([python.md](python.md) is the guide).\n\n" + \
    "".join(f"## `{module}`\n\n::: {module}\n\n" for module in PYTHON_MODULES)


def slugify(text: str) -> str:
    from pymdownx.slugs import slugify as make_slugify
    return make_slugify(case="lower")(text, "-")


def headings(lines: List[str]) -> List[Tuple[int, int, str]]:
    """(line index, level, text) of the Markdown headings outside fenced code."""
    found, fenced = [], False
    for index, line in enumerate(lines):
        if FENCE.match(line):
            fenced = not fenced
        elif not fenced:
            match = HEADING.match(line)
            if match:
                found.append((index, len(match.group(1)), match.group(2)))
    return found


def split_input_format(text: str) -> List[Tuple[str, str, List[str]]]:
    """(file name, title, lines) of each page: the first sections, then one page per `## ` section."""
    lines = text.splitlines()
    sections = [index for index, level, _ in headings(lines) if level == 2]
    first_end = lines.index(INPUT_FORMAT_FIRST_PAGE_ENDS_AT)
    pages = [("index.md", "Input format", lines[:first_end])]
    for start, end in zip(sections, sections[1:] + [len(lines)]):
        if start < first_end:
            continue
        title = lines[start][3:].strip()
        # The section's heading becomes the page's title; its anchor stays the same.
        body = ["# " + title] + lines[start + 1:end]
        pages.append((slugify(title) + ".md", title, body))
    return pages


def anchors_of(lines: List[str]) -> List[str]:
    return [slugify(text) for _, _, text in headings(lines)]


def relative(target: str, source: str) -> str:
    """The path from page `source` to page `target`, both relative to the site's root."""
    return "../" * source.count("/") + target


def rewrite_links(lines: List[str], source: str, page: str, anchor_pages: Dict[str, str]) -> List[str]:
    """Points the links of `source` (a file of the repository, shown as site page `page`) at the pages
    that now hold their targets and anchors; links out of docs/ become text."""
    def replace(match: "re.Match[str]") -> str:
        text, target = match.group(1), match.group(2)
        if re.match(r"^[a-z]+:", target):
            return match.group(0)
        path, _, anchor = target.partition("#")
        resolved = posixpath.normpath(posixpath.join(posixpath.dirname(source), path)) if path else source
        if resolved == "docs/" + INPUT_FORMAT:
            # An anchor found nowhere stays on the first page, where MkDocs reports it missing.
            holder = anchor_pages.get(anchor, "input-format/index.md")
        elif resolved.startswith("docs/") and resolved[len("docs/"):] not in NOT_ON_SITE:
            holder = resolved[len("docs/"):]
        else:
            return text if resolved in text else f"{text} (`{resolved}`)"
        fragment = "#" + anchor if anchor else ""
        return f"[{text}]({fragment})" if holder == page and anchor else f"[{text}]({relative(holder, page)}{fragment})"

    # Links may wrap across lines, so the text between code fences is rewritten as one piece.
    out: List[str] = []
    prose: List[str] = []
    fenced = False
    for line in lines + ["```"]:
        if FENCE.match(line):
            if not fenced:
                out += LINK.sub(replace, "\n".join(prose)).split("\n") if prose else []
                prose = []
            fenced = not fenced
            out.append(line)
        elif fenced:
            out.append(line)
        else:
            prose.append(line)
    return out[:-1]


def write_pages(pages_dir: Path) -> List[Tuple[str, str]]:
    """Writes every page; returns the input format's (title, path) in order, for the navigation."""
    if pages_dir.exists():
        shutil.rmtree(pages_dir)
    shutil.copytree(DOCS, pages_dir, ignore=shutil.ignore_patterns(*NOT_ON_SITE, INPUT_FORMAT))
    original = (DOCS / INPUT_FORMAT).read_text(encoding="utf-8")
    split = split_input_format(original)
    # The split keeps every line and every heading (a section's heading becomes its page's title).
    kept = [line for _, _, lines in split for line in lines]
    if len(kept) != len(original.splitlines()) or \
            sorted(anchors_of(kept)) != sorted(anchors_of(original.splitlines())):
        raise SystemExit(f"docs_site: splitting {INPUT_FORMAT} lost lines or headings")
    anchor_pages: Dict[str, str] = {}
    for name, _, lines in split:
        for anchor in anchors_of(lines):
            anchor_pages.setdefault(anchor, "input-format/" + name)
    (pages_dir / "input-format").mkdir()
    for name, _, lines in split:
        page = "input-format/" + name
        lines = rewrite_links(lines, "docs/" + INPUT_FORMAT, page, anchor_pages)
        (pages_dir / page).write_text("\n".join(lines) + "\n", encoding="utf-8")
    (pages_dir / "python-api.md").write_text(PYTHON_API_PAGE, encoding="utf-8")
    for _, name in PAGES + TUTORIALS:
        if name == "python-api.md":
            continue
        lines = (DOCS / name).read_text(encoding="utf-8").splitlines()
        lines = rewrite_links(lines, "docs/" + name, name, anchor_pages)
        (pages_dir / name).write_text("\n".join(lines) + "\n", encoding="utf-8")
    readme = (REPOSITORY / "README.md").read_text(encoding="utf-8").splitlines()
    readme = rewrite_links(readme, "README.md", "index.md", anchor_pages)
    (pages_dir / "index.md").write_text("\n".join(readme) + "\n", encoding="utf-8")
    return [(title, "input-format/" + name) for name, title, _ in split]


def mkdocs_config(pages_dir: Path, site_dir: Path, input_format: List[Tuple[str, str]]) -> str:
    nav = ["nav:", "  - Home: index.md", "  - Input format:"]
    nav += [f"      - {title!r}: {path}" for title, path in input_format]
    nav += ["  - Tutorials:"] + [f"      - {title!r}: {name}" for title, name in TUTORIALS]
    nav += [f"  - {title}: {name}" for title, name in PAGES]
    return "\n".join([
        "site_name: structmd",
        f"docs_dir: {pages_dir}",
        f"site_dir: {site_dir}",
        "theme: readthedocs",
        "use_directory_urls: false",
        *nav,
        "markdown_extensions:",
        "  - tables",
        "  - pymdownx.superfences",
        # --8<-- "examples/tutorials/x.py" in a tutorial's code block: the file, from the repository.
        "  - pymdownx.snippets:",
        f"      base_path: [{REPOSITORY}]",
        "      check_paths: true",
        # Lists indented by 2 as on GitHub, so the code blocks inside them stay code.
        "  - mdx_truly_sane_lists",
        "  - toc:",
        "      permalink: true",
        "      slugify: !!python/object/apply:pymdownx.slugs.slugify {kwds: {case: lower}}",
        "plugins:",
        "  - search",
        "  - mkdocstrings:",
        "      handlers:",
        "        python:",
        f"          paths: [{REPOSITORY / 'bindings' / 'python'}]",
        "          options: {show_source: false, heading_level: 3, members_order: source}",
        "validation:",
        "  omitted_files: warn",
        "  absolute_links: warn",
        "  unrecognized_links: warn",
        "  anchors: warn",
        "",
    ])


def main(output: str) -> int:
    try:
        import mkdocs  # noqa: F401
        import mdx_truly_sane_lists  # noqa: F401
        import mkdocstrings  # noqa: F401
        import pymdownx  # noqa: F401
    except ImportError as error:
        print(f"skipped: {error.name} is not installed (scripts/install-deps.sh installs it)")
        return SKIPPED
    out = Path(output).resolve()
    out.mkdir(parents=True, exist_ok=True)
    pages_dir, site_dir = out / "pages", out / "site"
    input_format = write_pages(pages_dir)
    config = out / "mkdocs.yml"
    config.write_text(mkdocs_config(pages_dir, site_dir, input_format), encoding="utf-8")
    built = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "--config-file", str(config)])
    if built.returncode == 0:
        print(f"docs_site: {site_dir / 'index.html'}")
    return built.returncode


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1]))
