#!/usr/bin/env python3
"""The coupling-loop tutorial (docs/tutorials/coupling-loop.md): its C program and its Python script
run the same loop on the same input and CPU engine, so they must print the same rows (step, the
field's energy, the potential energy, the mean distance from the centre) to 1e-9; the field's
energy must be k/2 sum |x|^2 of that distance's particles, so at least (k/2) N <|x|>^2 (Jensen), and
the tether must pull the particles in: the mean distance ends at least 5 % below where it started.

usage: check_coupling_tutorial.py C_PROGRAM PYTHON_SCRIPT INPUT_JSON [FIGURE.png]"""
import subprocess
import sys

import numpy as np

STIFFNESS = 0.5
PARTICLES = 400  # of examples/bead_spring.json


def rows(command):
    run = subprocess.run(command, capture_output=True, text=True, timeout=300)
    if run.returncode != 0:
        sys.exit(f"{command[0]} failed ({run.returncode}): {run.stderr}")
    return np.array([[float(v) for v in line.split()] for line in run.stdout.splitlines() if not line.startswith("#")])


c_program, python_script, input_json = sys.argv[1:4]
from_c = rows([c_program, input_json])
from_python = rows([sys.executable, python_script, input_json] + sys.argv[4:5])
problems = []
if from_c.shape != from_python.shape or len(from_c) < 2:
    problems.append(f"C printed {from_c.shape}, Python {from_python.shape}")
elif not np.allclose(from_c, from_python, rtol=1e-9, atol=0):
    problems.append(f"C and Python differ by up to {np.max(np.abs(from_c - from_python) / np.abs(from_c)):.2e}")
else:
    step, field, _, distance = from_c.T
    if np.any(field < 0.5 * STIFFNESS * PARTICLES * distance ** 2 * (1 - 1e-12)):
        problems.append("a field energy below (k/2) N <|x|>^2")
    if not distance[-1] < 0.95 * distance[0]:
        problems.append(f"mean distance {distance[0]:.3f} -> {distance[-1]:.3f}: the tether did not pull")
    if not np.all(np.diff(step) > 0):
        problems.append("steps do not advance")
for problem in problems:
    print("FAILED:", problem)
sys.exit(1 if problems else 0)
