#!/usr/bin/env python3
"""Runs the bundled polymer melt through the launcher (minimisation, then Langevin at T = 1) and
checks what it writes: a DCD of 12 frames of 1000 particles (steps 0, 500, ..., 5500), the
thermodynamics every 100 steps, an energy that the minimiser lowered, and a melt that reached its
temperature. The temperature bound: the kinetic temperature of N = 1000 particles fluctuates by
sqrt(2/(3N)) = 2.6% per sample; averaged over the last 20 samples (correlated over about
1/gamma = 2 time units = 400 steps, so about 5 independent ones) the mean stays within 5% of 1.
The bonds of the last frame have the Kremer-Grest length: FENE (K = 30, R0 = 1.5) against the WCA
repulsion that also acts between bonded beads puts the median near 0.97 (0.94 to 1.0 accepted);
without that repulsion the bonds shrink to about 0.6.

usage: check_polymer_melt.py LAUNCHER EXAMPLES_DIR [BACKEND]"""
import json
import os
import shutil
import statistics
import struct
import subprocess
import sys
import tempfile

launcher, examples = os.path.abspath(sys.argv[1]), sys.argv[2]
backend = sys.argv[3] if len(sys.argv) > 3 else "cpu"

with tempfile.TemporaryDirectory() as work:
    shutil.copy(os.path.join(examples, "polymer_melt.json"), work)
    run = subprocess.run([launcher, "run", "polymer_melt.json", "--backend", backend], cwd=work,
                         capture_output=True, text=True)
    if run.returncode == 77 or "no usable GPU" in run.stderr or "no CUDA backend" in run.stderr:
        sys.exit(77)
    if run.returncode != 0:
        sys.exit(f"launcher failed ({run.returncode}): {run.stderr}")

    with open(os.path.join(work, "polymer_melt.dcd"), "rb") as f:
        data = f.read()
    # Records are framed by their byte counts: header (84 bytes), title, then the atom count.
    _, magic, frames, first, interval = struct.unpack("<i4siii", data[:20])
    title_length = struct.unpack("<i", data[92:96])[0]
    atoms_at = 92 + 4 + title_length + 4 + 4
    atoms = struct.unpack("<i", data[atoms_at:atoms_at + 4])[0]
    problems = []
    if (magic, frames, first, interval, atoms) != (b"CORD", 12, 0, 500, 1000):
        problems.append(f"DCD header: frames {frames}, first step {first}, interval {interval}, atoms {atoms}")

    # The last frame: x, y and z records of 4 + 4 atoms + 4 bytes each, at the end of the file.
    record = 4 * atoms + 8
    last = data[len(data) - 3 * record:]
    x, y, z = (struct.unpack(f"<{atoms}f", last[k * record + 4:(k + 1) * record - 4]) for k in range(3))
    with open(os.path.join(work, "polymer_melt.json")) as f:
        document = json.load(f)
    box = document["global"]["ensemble"]["data"][0][0]
    lengths = []
    for i, j in document["topology"]["forceField"]["fene"]["data"]:
        d = [c[j] - c[i] for c in (x, y, z)]
        d = [v - L * round(v / L) for v, L in zip(d, box)]
        lengths.append(sum(v * v for v in d) ** 0.5)
    bond = statistics.median(lengths)
    if not 0.94 <= bond <= 1.0:
        problems.append(f"median FENE bond {bond:.3f} in the last frame, expected 0.94 to 1.0 (Kremer-Grest 0.97)")

    rows = []
    with open(os.path.join(work, "polymer_melt_thermo.dat")) as f:
        header = f.readline().lstrip("#").split()
        rows = [dict(zip(header, map(float, line.split()))) for line in f if line.strip()]
    steps = [int(r["step"]) for r in rows]
    if steps != list(range(0, 5501, 100)):
        problems.append(f"thermodynamics at steps {steps[:3]}...{steps[-3:]}, expected 0, 100, ..., 5500")
    minimised = [r["potential"] for r in rows if r["step"] <= 500]
    # The floor is the bonds' own energy, FENE + WCA at about 0.97: some 20 per bond, 19,000 in all.
    if not minimised[-1] < 0.6 * minimised[0]:
        problems.append(f"the minimiser did not lower the energy: {minimised[0]} -> {minimised[-1]}")
    temperature = sum(r["temperature"] for r in rows[-20:]) / 20
    if abs(temperature - 1.0) > 0.05:
        problems.append(f"mean temperature of the last 20 samples {temperature:.3f}, expected 1 +- 0.05")
    if problems:
        sys.exit("\n".join(problems))
    print(f"polymer melt: 12 frames, T = {temperature:.3f}, energy {minimised[0]:.1f} -> {minimised[-1]:.1f}, "
          f"median bond {bond:.3f}")
