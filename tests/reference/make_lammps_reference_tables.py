#!/usr/bin/env python3
"""Builds the LAMMPS reference data that tests/tabulated/test_tabulated_lammps.cpp checks structmd's
tabulated potentials against (["NonBonded","Tabulated"], ["Bond2","Tabulated"], ["Bond3","Tabulated"]).

Table files (data/tables/), written from analytic potentials in LAMMPS's table format:
  pair.table   LJ       4 (r^-12 - r^-6) on 0.8 <= r <= 3.0, 221 points, r listed, no keywords
               SOFT     A (1 + cos(pi r / rc)), A = 2, rc = 2.5, "N 161 R 0.5 2.5 FPRIME lo hi"
               LJ_RSQ   LJ with sigma 1.1 on points even in r^2, "N 300 RSQ 0.85 2.8"
  bond.table   HARM     1/2 K (r - r0)^2, K = 50, r0 = 1, 0.5 <= r <= 1.6, "N 111 FP -50 -50 EQ 1.0"
               MORSE    D (1 - exp(-a (r - r0)))^2, D = 3, a = 2, r0 = 1.05, 0.4 <= r <= 2, "N 81"
  angle.table  HARM     1/2 K (theta - theta0)^2, K = 20 / rad^2, theta0 = 110 degrees, 0..180 degrees
                        every degree, "N 181 FP lo hi EQ 110"; LAMMPS reads theta in degrees and the
                        force as -dU/d(theta in degrees), and FP in energy/degree^2

Cases (each data/<case>.json, the structmd input, and data/<case>.lammps.json, LAMMPS's per-atom
forces, per-atom energies and total energy):
  table_pair   16 particles of types A, B in a periodic box of 8 (several pairs across the boundary),
               pair_style table spline 1000: A-A LJ, A-B SOFT cut at 2.2 (pair_coeff's cutoff), B-B
               LJ_RSQ.
  table_bonds  an 8-particle chain across the periodic boundary of a box of 6: its bonds with
               bond_style table spline 500 (HARM on the even bonds, MORSE on the odd ones: two
               structmd entries) and its angles with angle_style table spline 361.

The structmd inputs name the table files relative to tests/reference/data (the test makes them
absolute). Before writing, LAMMPS's forces and energies are checked against the analytic potentials
(to 1e-5 relative, 1e-4 for the coarser dihedral tables: the tables are interpolations), which shows
that the files say what is meant.

The script is deterministic (numpy's PCG64 with fixed seeds).
Usage: python3 tests/reference/make_lammps_reference_tables.py [--lmp /usr/bin/lmp]
"""
import argparse
import json
import math
import pathlib
import subprocess
import tempfile

import numpy as np

DATA = pathlib.Path(__file__).resolve().parent / "data"
TABLES = DATA / "tables"
PAIR_N = 1000
BOND_N = 500
ANGLE_N = 361


# ---- analytic potentials: (energy, force = -dU/dx, dforce/dx) ----------------------------------

def lj(r, sigma=1.0):
    s6 = (sigma / r) ** 6
    return 4 * (s6 * s6 - s6), 24 * (2 * s6 * s6 - s6) / r, -24 * (26 * s6 * s6 - 7 * s6) / r**2


def soft(r, a=2.0, rc=2.5):
    k = math.pi / rc
    return a * (1 + math.cos(k * r)), a * k * math.sin(k * r), a * k * k * math.cos(k * r)


def harmonic(x, k, x0):
    return 0.5 * k * (x - x0) ** 2, -k * (x - x0), -k


def morse(r, d=3.0, a=2.0, r0=1.05):
    e = math.exp(-a * (r - r0))
    return d * (1 - e) ** 2, -2 * d * a * e * (1 - e), 2 * d * a * a * e * (1 - 2 * e)


ANGLE_K = 20.0
ANGLE_THETA0 = 110.0
BOND_K = 50.0


def angle_potential(theta):
    return harmonic(theta, ANGLE_K, ANGLE_THETA0 * math.pi / 180)


# ---- table files ---------------------------------------------------------------------------------

def section(keyword, parameters, rows):
    lines = [keyword, parameters, ""]
    lines += [f"{i + 1} {x!r} {e!r} {f!r}" for i, (x, e, f) in enumerate(rows)]
    return "\n".join(lines) + "\n\n"


DIHEDRAL_N = 360


def dihedral_one(phi):
    """1.5 (1 + cos(2 phi - 30 degrees)): energy and -dU/dphi."""
    d = math.radians(30.0)
    return 1.5 * (1 + math.cos(2 * phi - d)), 3.0 * math.sin(2 * phi - d)


def dihedral_two(phi):
    """0.8 (1 + cos(phi - 0.3)) + 0.4 (1 + cos(3 phi))."""
    return (0.8 * (1 + math.cos(phi - 0.3)) + 0.4 * (1 + math.cos(3 * phi)),
            0.8 * math.sin(phi - 0.3) + 1.2 * math.sin(3 * phi))


def write_tables():
    TABLES.mkdir(parents=True, exist_ok=True)
    lj_r = [0.8 + 0.01 * i for i in range(221)]
    soft_r = [0.5 + 2.0 * i / 160 for i in range(161)]
    rsq_r = [math.sqrt(0.85**2 + (2.8**2 - 0.85**2) * i / 299) for i in range(300)]
    pair = "# structmd reference: pair tables from analytic potentials\n\n"
    pair += section("LJ", "N 221", [(r, *lj(r)[:2]) for r in lj_r])
    pair += section("SOFT", f"N 161 R 0.5 2.5 FPRIME {soft(0.5)[2]!r} {soft(2.5)[2]!r}",
                    [(r, *soft(r)[:2]) for r in soft_r])
    pair += section("LJ_RSQ", "N 300 RSQ 0.85 2.8", [(r, *lj(r, 1.1)[:2]) for r in rsq_r])
    (TABLES / "pair.table").write_text(pair)

    bond = "# structmd reference: bond tables\n\n"
    bond += section("HARM", f"N 111 FP {-BOND_K!r} {-BOND_K!r} EQ 1.0",
                    [(r, *harmonic(r, BOND_K, 1.0)[:2]) for r in (0.5 + 0.01 * i for i in range(111))])
    bond += section("MORSE", "N 81", [(r, *morse(r)[:2]) for r in (0.4 + 0.02 * i for i in range(81))])
    (TABLES / "bond.table").write_text(bond)

    degree = math.pi / 180
    rows = []
    for i in range(181):
        e, f, _ = angle_potential(i * degree)
        rows.append((float(i), e, f * degree))  # -dU/d(degree)
    slope = -ANGLE_K * degree * degree  # d(force per degree)/d(degree)
    angle = "# structmd reference: angle table (degrees)\n\n"
    angle += section("HARM", f"N 181 FP {slope!r} {slope!r} EQ 110.0", rows)
    (TABLES / "angle.table").write_text(angle)

    dihedral = "# structmd reference: dihedral tables\n\n"
    rows = []
    for k in range(72):  # -180 .. 175 degrees; force per degree
        e, f = dihedral_one(math.radians(-180.0 + 5 * k))
        rows.append((-180.0 + 5 * k, e, f * degree))
    dihedral += section("DIH", "N 72 DEGREES", rows)
    lines = ["DIH_NOF", "N 90 NOF RADIANS", ""]
    for k in range(90):
        phi = 2 * math.pi * k / 90
        lines.append(f"{k + 1} {phi!r} {dihedral_two(phi)[0]!r}")
    dihedral += "\n".join(lines) + "\n"
    (TABLES / "dihedral.table").write_text(dihedral)


# ---- configurations ------------------------------------------------------------------------------

def minimum_image(d, box):
    return d - box * np.round(d / box)


def pair_configuration():
    box = 8.0
    rng = np.random.default_rng(20261123)
    # Pairs across each face first (closer than the cutoffs through the boundary), then random ones.
    positions = [np.array([3.7, 0.1, 0.2]), np.array([-3.5, 0.4, -0.3]),
                 np.array([0.5, 3.6, 1.0]), np.array([0.9, -3.3, 1.4]),
                 np.array([-1.0, -1.2, 3.8]), np.array([-1.6, -0.4, -3.7])]
    while len(positions) < 16:
        trial = rng.uniform(-box / 2, box / 2, 3)
        if all(np.linalg.norm(minimum_image(trial - p, box)) > 0.95 for p in positions):
            positions.append(trial)
    types = ["A" if i % 2 == 0 else "B" for i in range(16)]
    return box, np.array(positions), types


def chain_configuration():
    box = 6.0
    rng = np.random.default_rng(7)
    positions = [np.array([2.4, 2.5, 2.6])]
    previous = np.array([1.0, 0.0, 0.0])
    while len(positions) < 8:
        d = rng.normal(size=3)
        d /= np.linalg.norm(d)
        if np.dot(d, previous) > 0.6 or np.dot(d, previous) < -0.7:
            continue  # keep angles between about 45 and 135 degrees... of the chain's direction
        length = rng.uniform(0.75, 1.35)
        nxt = positions[-1] + length * d
        positions.append(nxt)
        previous = d
    wrapped = [minimum_image(p, box) for p in positions]
    return box, np.array(wrapped)


# ---- LAMMPS --------------------------------------------------------------------------------------

def run_lammps(lmp, data, script, natoms):
    with tempfile.TemporaryDirectory(prefix="structmd-tables-") as tmp:
        work = pathlib.Path(tmp)
        (work / "system.data").write_text(data)
        (work / "in.reference").write_text(script)
        run = subprocess.run([lmp, "-in", "in.reference", "-log", "none", "-screen", "screen.txt", "-nocite"],
                             cwd=work)
        if run.returncode != 0:
            raise RuntimeError((work / "screen.txt").read_text()[-3000:])
        dump = (work / "atoms.dump").read_text().splitlines()
        total = float((work / "total.txt").read_text())
        version = subprocess.run([lmp, "-h"], capture_output=True, text=True).stdout.strip().splitlines()[0]
    header = next(k for k, line in enumerate(dump) if line.startswith("ITEM: ATOMS"))
    table = np.array([[float(v) for v in line.split()] for line in dump[header + 1:]])
    assert np.array_equal(table[:, 0], np.arange(1, natoms + 1))
    return {"lammps_version": version, "num_particles": natoms, "forces": table[:, 1:4].tolist(),
            "particle_energies": table[:, 4].tolist(), "energy": total}


def lammps_data(box, positions, atom_types, ntypes, bonds=(), angles=(), style="atomic", dihedrals=()):
    half = box / 2
    lines = ["structmd table reference", "", f"{len(positions)} atoms", f"{ntypes} atom types"]
    if bonds:
        lines += [f"{len(bonds)} bonds", "2 bond types", f"{len(angles)} angles", "1 angle types"]
    if dihedrals:
        lines += [f"{len(dihedrals)} dihedrals", "2 dihedral types"]
    lines += ["", f"{-half!r} {half!r} xlo xhi", f"{-half!r} {half!r} ylo yhi", f"{-half!r} {half!r} zlo zhi",
              "", "Masses", ""] + [f"{t + 1} 1.0" for t in range(ntypes)] + ["", "Atoms", ""]
    for i, (p, t) in enumerate(zip(positions, atom_types)):
        molecule = "1 " if style == "molecular" else ""
        lines.append(f"{i + 1} {molecule}{t} {float(p[0])!r} {float(p[1])!r} {float(p[2])!r}")
    if bonds:
        lines += ["", "Bonds", ""] + [f"{k + 1} {t} {i + 1} {j + 1}" for k, (t, i, j) in enumerate(bonds)]
        lines += ["", "Angles", ""] + [f"{k + 1} 1 {i + 1} {j + 1} {l + 1}" for k, (i, j, l) in enumerate(angles)]
    if dihedrals:
        lines += ["", "Dihedrals", ""] + [f"{k + 1} {t} {i + 1} {j + 1} {l + 1} {m + 1}"
                                          for k, (t, i, j, l, m) in enumerate(dihedrals)]
    return "\n".join(lines) + "\n"


def lammps_script(style, interactions):
    return "\n".join(["units lj", f"atom_style {style}", "boundary p p p", "atom_modify map array",
                      "read_data system.data"] + interactions +
                     ["neighbor 0.3 bin", "compute pe all pe/atom", "thermo_modify norm no",
                      "dump atoms all custom 1 atoms.dump id fx fy fz c_pe",
                      "dump_modify atoms format float %.17g sort id", "run 0",
                      'print "$(pe:%.17g)" file total.txt screen no']) + "\n"


# ---- analytic checks -----------------------------------------------------------------------------

def check(name, lammps, forces, energy, tolerance=1e-5):
    f = np.array(lammps["forces"])
    scale = np.max(np.abs(forces))
    deviation = np.max(np.abs(f - forces)) / scale
    energy_deviation = abs(lammps["energy"] - energy) / abs(energy)
    print(f"{name}: LAMMPS against the analytic potentials: forces {deviation:.2e}, energy {energy_deviation:.2e}")
    assert deviation < tolerance and energy_deviation < tolerance, "the tables do not say what is meant"


def analytic_pair(box, positions, types):
    n = len(positions)
    forces = np.zeros((n, 3))
    energy = 0.0
    for i in range(n):
        for j in range(i + 1, n):
            d = minimum_image(positions[j] - positions[i], box)
            r = np.linalg.norm(d)
            pair = {"AA": (lj, 3.0), "AB": (soft, 2.2), "BA": (soft, 2.2),
                    "BB": (lambda x: lj(x, 1.1), 2.8)}[types[i] + types[j]]
            if r >= pair[1]:
                continue
            e, f, _ = pair[0](r)
            energy += e
            forces[j] += f * d / r
            forces[i] -= f * d / r
    return forces, energy


def chain_terms(box, positions):
    bonds = [(1 if k % 2 == 0 else 2, k, k + 1) for k in range(len(positions) - 1)]
    angles = [(k, k + 1, k + 2) for k in range(len(positions) - 2)]
    return bonds, angles


def analytic_chain(box, positions, bonds, angles):
    forces = np.zeros_like(positions)
    energy = 0.0
    for t, i, j in bonds:
        d = minimum_image(positions[j] - positions[i], box)
        r = np.linalg.norm(d)
        e, f, _ = harmonic(r, BOND_K, 1.0) if t == 1 else morse(r)
        energy += e
        forces[j] += f * d / r
        forces[i] -= f * d / r
    for i, j, k in angles:
        a = minimum_image(positions[i] - positions[j], box)
        b = minimum_image(positions[k] - positions[j], box)
        c = np.dot(a, b) / (np.linalg.norm(a) * np.linalg.norm(b))
        theta = math.acos(c)
        e, f, _ = angle_potential(theta)
        energy += e
        # dtheta/da = -(b/|b| - c a/|a|) / (|a| sin theta)
        s = math.sin(theta)
        da = -(b / np.linalg.norm(b) - c * a / np.linalg.norm(a)) / (np.linalg.norm(a) * s)
        db = -(a / np.linalg.norm(a) - c * b / np.linalg.norm(b)) / (np.linalg.norm(b) * s)
        forces[i] += f * da
        forces[k] += f * db
        forces[j] -= f * (da + db)
    return forces, energy


# ---- structmd inputs -----------------------------------------------------------------------------

def structmd_input(name, box, positions, types, type_names, forcefield):
    return {
        "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": name, "seed": 1}}},
        "global": {
            "units": {"type": ["Units", "None"]},
            "types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"],
                      "data": [[t, 1.0, 0.5, 0.0] for t in type_names]},
            "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"], "data": [[[box] * 3, 1.0]]},
        },
        "integrator": {
            "vv": {"type": ["Verlet", "VelocityVerlet"], "parameters": {"timeStep": 0.001}},
            "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
                         "data": [[1, "vv", 1000]]},
        },
        "state": {"labels": ["id", "position"], "data": [[i, [float(c) for c in p]] for i, p in enumerate(positions)]},
        "topology": {"structure": {"labels": ["id", "type"], "data": [[i, t] for i, t in enumerate(types)]},
                     "forceField": forcefield},
    }


def write_json(path, document):
    path.write_text(json.dumps(document, indent=1) + "\n")


def pair_case(lmp):
    box, positions, types = pair_configuration()
    lammps = run_lammps(lmp, lammps_data(box, positions, [1 if t == "A" else 2 for t in types], 2),
                        lammps_script("atomic", [f"pair_style table spline {PAIR_N}",
                                                 f"pair_coeff 1 1 {TABLES}/pair.table LJ",
                                                 f"pair_coeff 1 2 {TABLES}/pair.table SOFT 2.2",
                                                 f"pair_coeff 2 2 {TABLES}/pair.table LJ_RSQ"]), len(positions))
    check("table_pair", lammps, *analytic_pair(box, positions, types))
    forcefield = {
        "nl": {"type": ["VerletConditionalListSet", "all"], "parameters": {"cutOffVerletFactor": 1.1}},
        "table": {"type": ["NonBonded", "Tabulated"], "parameters": {"condition": "all", "N": PAIR_N},
                  "labels": ["name_i", "name_j", "file", "keyword", "cutOff"],
                  "data": [["A", "A", "tables/pair.table", "LJ", 3.0],
                           ["A", "B", "tables/pair.table", "SOFT", 2.2],
                           ["B", "B", "tables/pair.table", "LJ_RSQ", 2.8]]},
    }
    write_json(DATA / "table_pair.json", structmd_input("table_pair", box, positions, types, ["A", "B"], forcefield))
    write_json(DATA / "table_pair.lammps.json", lammps)


def bonds_case(lmp):
    box, positions = chain_configuration()
    bonds, angles = chain_terms(box, positions)
    lammps = run_lammps(lmp, lammps_data(box, positions, [1] * len(positions), 1, bonds, angles, "molecular"),
                        lammps_script("molecular", [f"bond_style table spline {BOND_N}",
                                                    f"bond_coeff 1 {TABLES}/bond.table HARM",
                                                    f"bond_coeff 2 {TABLES}/bond.table MORSE",
                                                    f"angle_style table spline {ANGLE_N}",
                                                    f"angle_coeff 1 {TABLES}/angle.table HARM"]), len(positions))
    check("table_bonds", lammps, *analytic_chain(box, positions, bonds, angles))
    forcefield = {
        "harm": {"type": ["Bond2", "Tabulated"],
                 "parameters": {"N": BOND_N, "file": "tables/bond.table", "keyword": "HARM"},
                 "labels": ["id_i", "id_j"], "data": [[i, j] for t, i, j in bonds if t == 1]},
        "morse": {"type": ["Bond2", "Tabulated"],
                  "parameters": {"N": BOND_N, "file": "tables/bond.table", "keyword": "MORSE"},
                  "labels": ["id_i", "id_j"], "data": [[i, j] for t, i, j in bonds if t == 2]},
        "angles": {"type": ["Bond3", "Tabulated"],
                   "parameters": {"N": ANGLE_N, "file": "tables/angle.table", "keyword": "HARM"},
                   "labels": ["id_i", "id_j", "id_k"], "data": [list(a) for a in angles]},
    }
    write_json(DATA / "table_bonds.json",
               structmd_input("table_bonds", box, positions, ["A"] * len(positions), ["A"], forcefield))
    write_json(DATA / "table_bonds.lammps.json", lammps)


def iupac_dihedral(p0, p1, p2, p3, box):
    b1 = minimum_image(p1 - p0, box)
    b2 = minimum_image(p2 - p1, box)
    b3 = minimum_image(p3 - p2, box)
    m, n = np.cross(b1, b2), np.cross(b2, b3)
    return math.atan2(np.linalg.norm(b2) * np.dot(b1, n), np.dot(m, n))


def analytic_dihedrals(box, positions, dihedrals):
    def energy(x):
        return sum((dihedral_one if t == 1 else dihedral_two)(iupac_dihedral(x[i], x[j], x[k], x[l], box))[0]
                   for t, i, j, k, l in dihedrals)
    forces = np.zeros_like(positions)
    h = 1e-6
    for a in range(len(positions)):
        for c in range(3):
            up, down = positions.copy(), positions.copy()
            up[a, c] += h
            down[a, c] -= h
            forces[a, c] = -(energy(up) - energy(down)) / (2 * h)
    return forces, energy(positions)


def dihedrals_case(lmp):
    box, positions = chain_configuration()
    dihedrals = [(1 if k % 2 == 0 else 2, k, k + 1, k + 2, k + 3) for k in range(len(positions) - 3)]
    lammps = run_lammps(lmp, lammps_data(box, positions, [1] * len(positions), 1, style="molecular",
                                         dihedrals=dihedrals),
                        lammps_script("molecular", [f"dihedral_style table spline {DIHEDRAL_N}",
                                                    f"dihedral_coeff 1 {TABLES}/dihedral.table DIH",
                                                    f"dihedral_coeff 2 {TABLES}/dihedral.table DIH_NOF"]),
                        len(positions))
    # 72 and 90 points per turn; the NOF table's force is the derivative of its energy spline.
    check("table_dihedrals", lammps, *analytic_dihedrals(box, positions, dihedrals), tolerance=1e-4)
    forcefield = {
        name: {"type": ["Bond4", "Tabulated"],
               "parameters": {"N": DIHEDRAL_N, "file": "tables/dihedral.table", "keyword": keyword},
               "labels": ["id_i", "id_j", "id_k", "id_l"], "data": [[i, j, k, l] for t, i, j, k, l in dihedrals if t == t0]}
        for name, keyword, t0 in (("dih", "DIH", 1), ("dihNof", "DIH_NOF", 2))}
    write_json(DATA / "table_dihedrals.json",
               structmd_input("table_dihedrals", box, positions, ["A"] * len(positions), ["A"], forcefield))
    write_json(DATA / "table_dihedrals.lammps.json", lammps)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--lmp", default="/usr/bin/lmp")
    args = parser.parse_args()
    write_tables()
    pair_case(args.lmp)
    bonds_case(args.lmp)
    dihedrals_case(args.lmp)


if __name__ == "__main__":
    main()
