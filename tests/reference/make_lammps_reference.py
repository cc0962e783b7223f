#!/usr/bin/env python3
"""Builds the LAMMPS reference data that tests/physics/test_lammps_reference.cpp checks structmd against.

For each case this writes
  data/<case>.json         the structmd input (UAMMD-structured JSON),
  data/<case>.lammps.json  what LAMMPS (Debian's `lmp`, serial) computes for the same configuration:
                           per-atom forces and energies, energy per structmd forceField entry and the
                           pressure virial tensor W (W_ab = sum over pairs of r_a F_b, so that the virial
                           pressure is W / V; in `units lj` nktv2p = 1).

The script is deterministic (its own SplitMix64 generator with fixed seeds, independent of numpy's
version): re-running it reproduces the files, up to the last bit of LAMMPS's own arithmetic.
An independent numpy evaluation of the same physics is checked against LAMMPS's numbers before anything
is written, so an extraction mistake (a units factor, a sign, a missed normalisation) cannot slip in.

Usage: python3 tests/reference/make_lammps_reference.py [--lmp /usr/bin/lmp]
"""
import argparse
import json
import pathlib
import subprocess
import tempfile

import numpy as np

DATA_DIR = pathlib.Path(__file__).resolve().parent / "data"

DENSITY = 0.8
FCC_CELLS = 5  # 4 * 5^3 = 500 particles
LJ_EPSILON = 1.0
LJ_SIGMA = 1.0
LJ_CUTOFF_FACTOR = 2.5
NEIGHBOUR_LIST_FACTOR = 1.2
MIN_DISTANCE = 0.85
NOISE_AMPLITUDE = 0.15
# A pair this close to the sharp, unshifted cutoff could fall on either side of it in two codes that
# round differently; the configuration is rejected if one exists.
CUTOFF_GUARD = 1e-8

CHAIN_LENGTH = 10
# Bond2 Harmonic rows alternate between two (K, r0) pairs so that the per-bond columns are really read;
# the HarmonicCommon_K_r0 entry takes the parameters of the brief.
PER_BOND_PARAMETERS = [(100.0, 1.0), (120.0, 0.95)]
COMMON_BOND_K = 100.0
COMMON_BOND_R0 = 1.0


class SplitMix64:
    """Tiny, fully specified generator: the files must not depend on numpy's distribution code."""

    MASK = (1 << 64) - 1

    def __init__(self, seed):
        self.state = seed & self.MASK

    def next_u64(self):
        self.state = (self.state + 0x9E3779B97F4A7C15) & self.MASK
        z = self.state
        z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & self.MASK
        z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & self.MASK
        return z ^ (z >> 31)

    def uniform(self, low, high):
        return low + (high - low) * ((self.next_u64() >> 11) * 2.0**-53)


def wrap(x, box_length):
    """Maps coordinates into [-L/2, L/2), guarding against rounding onto the upper face."""
    wrapped = x - box_length * np.floor((x + 0.5 * box_length) / box_length)
    wrapped[wrapped >= 0.5 * box_length] -= box_length
    return wrapped


def minimum_image(d, box_length):
    return d - box_length * np.round(d / box_length)


def fcc_liquid_configuration(seed):
    """An fcc lattice at DENSITY, every site displaced by uniform noise; no pair closer than MIN_DISTANCE.

    Sites are numbered with z fastest and the four basis sites innermost, so consecutive ids are nearest
    neighbours (also across the periodic boundary): chains of consecutive ids make sensible polymers.
    """
    lattice_constant = (4.0 / DENSITY) ** (1.0 / 3.0)
    box_length = FCC_CELLS * lattice_constant
    basis = np.array([[0.0, 0.0, 0.0], [0.5, 0.5, 0.0], [0.5, 0.0, 0.5], [0.0, 0.5, 0.5]])
    sites = np.array([(np.array([ix, iy, iz]) + b) * lattice_constant
                      for ix in range(FCC_CELLS) for iy in range(FCC_CELLS) for iz in range(FCC_CELLS)
                      for b in basis])
    rng = SplitMix64(seed)
    positions = np.empty_like(sites)
    for i, site in enumerate(sites):
        while True:
            trial = wrap(site - 0.5 * box_length
                         + np.array([rng.uniform(-NOISE_AMPLITUDE, NOISE_AMPLITUDE) for _ in range(3)]),
                         box_length)
            if i == 0:
                break
            d = minimum_image(positions[:i] - trial, box_length)
            if np.sqrt((d * d).sum(axis=1)).min() >= MIN_DISTANCE:
                break
        positions[i] = trial
    return positions, box_length


def pair_distances(positions, box_length):
    d = minimum_image(positions[None, :, :] - positions[:, None, :], box_length)
    return d, np.sqrt((d * d).sum(axis=2))


def chain_bonds(n_particles):
    """Bonds between consecutive ids within chains of CHAIN_LENGTH; even bonds of a chain go to the
    per-bond entry (alternating parameter sets by chain), odd bonds to the common entry."""
    per_bond, common = [], []
    for chain_start in range(0, n_particles, CHAIN_LENGTH):
        chain = chain_start // CHAIN_LENGTH
        for k in range(CHAIN_LENGTH - 1):
            i, j = chain_start + k, chain_start + k + 1
            if k % 2 == 0:
                K, r0 = PER_BOND_PARAMETERS[chain % len(PER_BOND_PARAMETERS)]
                per_bond.append((i, j, K, r0))
            else:
                common.append((i, j, COMMON_BOND_K, COMMON_BOND_R0))
    return per_bond, common


def numpy_reference(positions, box_length, bond_sets):
    """Direct O(N^2) evaluation of the same physics, used only to validate what is read from LAMMPS."""
    n = len(positions)
    d, r = pair_distances(positions, box_length)  # d[i, j] = r_j - r_i
    cutoff = LJ_CUTOFF_FACTOR * LJ_SIGMA
    mask = (r < cutoff) & ~np.eye(n, dtype=bool)
    safe_r = np.where(mask, r, 1.0)
    sr6 = (LJ_SIGMA / safe_r) ** 6
    u = np.where(mask, 4.0 * LJ_EPSILON * (sr6 * sr6 - sr6), 0.0)
    du_dr = np.where(mask, 4.0 * LJ_EPSILON * (-12.0 * sr6 * sr6 + 6.0 * sr6) / safe_r, 0.0)
    # Force on i from j: U'(r) (r_j - r_i) / r.
    f_ij = (du_dr / safe_r)[:, :, None] * d
    forces = f_ij.sum(axis=1)
    particle_energy = 0.5 * u.sum(axis=1)
    # W = sum over pairs (r_i - r_j) (x) F_ij: each unordered pair once.
    virial = 0.5 * np.einsum("ija,ijb->ab", -d, f_ij)
    terms = {"lj": 0.5 * u.sum()}
    for name, bonds in bond_sets.items():
        energy = 0.0
        for i, j, K, r0 in bonds:
            dij = minimum_image(positions[j] - positions[i], box_length)
            rij = np.linalg.norm(dij)
            energy += 0.5 * K * (rij - r0) ** 2
            f_i = K * (rij - r0) * dij / rij
            forces[i] += f_i
            forces[j] -= f_i
            particle_energy[i] += 0.25 * K * (rij - r0) ** 2
            particle_energy[j] += 0.25 * K * (rij - r0) ** 2
            virial += np.outer(-dij, f_i)
        terms[name] = energy
    return forces, particle_energy, terms, virial


def json_row(values):
    return json.dumps(values, separators=(", ", ": "))


def structmd_input(case, positions, box_length, bond_sets):
    """The structmd input text, one table row per line; floats are written by repr (exact round trip)."""
    forcefield = [
        '      "nl": {"type": ["VerletConditionalListSet", "all"], '
        f'"parameters": {{"cutOffVerletFactor": {NEIGHBOUR_LIST_FACTOR!r}}}}}',
        '      "lj": {"type": ["NonBonded", "LennardJonesType1"], '
        f'"parameters": {{"cutOffFactor": {LJ_CUTOFF_FACTOR!r}, "condition": "all"}},\n'
        '             "labels": ["name_i", "name_j", "epsilon", "sigma"], '
        f'"data": [["A", "A", {LJ_EPSILON!r}, {LJ_SIGMA!r}]]}}',
    ]
    if "bonds" in bond_sets:
        rows = ",\n        ".join(json_row([i, j, K, r0]) for i, j, K, r0 in bond_sets["bonds"])
        forcefield.append('      "bonds": {"type": ["Bond2", "Harmonic"], "labels": ["id_i", "id_j", "K", "r0"],\n'
                          f'        "data": [\n        {rows}]}}')
    if "bondsCommon" in bond_sets:
        rows = ",\n        ".join(json_row([i, j]) for i, j, _, _ in bond_sets["bondsCommon"])
        forcefield.append('      "bondsCommon": {"type": ["Bond2", "HarmonicCommon_K_r0"], '
                          f'"parameters": {{"K": {COMMON_BOND_K!r}, "r0": {COMMON_BOND_R0!r}}},\n'
                          f'        "labels": ["id_i", "id_j"], "data": [\n        {rows}]}}')
    state_rows = ",\n    ".join(json_row([i, [float(c) for c in p]]) for i, p in enumerate(positions))
    structure_rows = ", ".join(json_row([i, "A"]) for i in range(len(positions)))
    box = json_row([float(box_length)] * 3)
    forcefield_text = ",\n".join(forcefield)
    return f"""{{
  "system": {{"info": {{"type": ["Simulation", "Information"], "parameters": {{"name": "{case}", "seed": 1}}}}}},
  "global": {{
    "units": {{"type": ["Units", "None"]}},
    "types": {{"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"], "data": [["A", 1.0, 0.5, 0.0]]}},
    "ensemble": {{"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"], "data": [[{box}, 1.0]]}},
    "fundamental": {{"type": ["Fundamental", "Time"], "parameters": {{"timeStep": 0.005}}}}
  }},
  "integrator": {{
    "vv": {{"type": ["Verlet", "VelocityVerlet"], "parameters": {{"timeStep": 0.005}}}},
    "schedule": {{"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"], "data": [[1, "vv", 100000]]}}
  }},
  "state": {{"labels": ["id", "position"], "data": [
    {state_rows}]}},
  "topology": {{
    "structure": {{"labels": ["id", "type"], "data": [{structure_rows}]}},
    "forceField": {{
{forcefield_text}
    }}
  }}
}}
"""


def lammps_bond_types(bond_sets):
    """One LAMMPS bond type per distinct (entry, K, r0); LAMMPS's harmonic is K_lmp (r - r0)^2, K_lmp = K/2."""
    types = {}
    for name, bonds in bond_sets.items():
        for _, _, K, r0 in bonds:
            types.setdefault((name, K, r0), len(types) + 1)
    return types


def lammps_data(positions, box_length, bond_sets, bond_types):
    half = 0.5 * box_length
    has_bonds = bool(bond_sets)
    lines = ["structmd reference configuration", "", f"{len(positions)} atoms", "1 atom types"]
    n_bonds = sum(len(b) for b in bond_sets.values())
    if has_bonds:
        lines += [f"{n_bonds} bonds", f"{len(bond_types)} bond types"]
    lines += ["", f"{-half:.17g} {half:.17g} xlo xhi", f"{-half:.17g} {half:.17g} ylo yhi",
              f"{-half:.17g} {half:.17g} zlo zhi", "", "Masses", "", "1 1.0", "", "Atoms", ""]
    for i, (x, y, z) in enumerate(positions):
        molecule = f"{i // CHAIN_LENGTH + 1} " if has_bonds else ""
        lines.append(f"{i + 1} {molecule}1 {x:.17g} {y:.17g} {z:.17g}")
    if has_bonds:
        lines += ["", "Bonds", ""]
        bond_id = 1
        for name, bonds in bond_sets.items():
            for i, j, K, r0 in bonds:
                lines.append(f"{bond_id} {bond_types[(name, K, r0)]} {i + 1} {j + 1}")
                bond_id += 1
    return "\n".join(lines) + "\n"


def lammps_script(bond_sets, bond_types):
    """Evaluates once with every term on, then once per bond entry with the other entries' K set to 0,
    which gives LAMMPS's energy of each structmd bond entry on its own."""
    has_bonds = bool(bond_sets)
    cutoff = LJ_CUTOFF_FACTOR * LJ_SIGMA
    lines = ["units lj", f"atom_style {'bond' if has_bonds else 'atomic'}", "boundary p p p",
             "atom_modify map array", "read_data system.data",
             f"pair_style lj/cut {cutoff!r}", f"pair_coeff 1 1 {LJ_EPSILON!r} {LJ_SIGMA!r} {cutoff!r}",
             "pair_modify shift no", "neighbor 0.3 bin", "neigh_modify delay 0 every 1 check yes"]
    if has_bonds:
        lines += ["bond_style harmonic", "special_bonds lj/coul 1.0 1.0 1.0"]
        lines += [f"bond_coeff {t} {K / 2.0!r} {r0!r}" for (_, K, r0), t in bond_types.items()]
    lines += ["compute peAtom all pe/atom", "compute peAtomPair all pe/atom pair",
              "compute pePair all pe pair", "compute virial all pressure NULL virial"]
    per_atom = "c_peAtom c_peAtomPair"
    thermo = "step c_pePair c_virial[1] c_virial[2] c_virial[3] c_virial[4] c_virial[5] c_virial[6]"
    if has_bonds:
        lines += ["compute peAtomBond all pe/atom bond", "compute peBond all pe bond"]
        per_atom += " c_peAtomBond"
        thermo += " c_peBond"
    lines += [f"thermo_style custom {thermo}",
              f"dump atoms all custom 1 atoms.dump id fx fy fz {per_atom}",
              "dump_modify atoms format float %.17g sort id", "run 0", "undump atoms"]
    totals = ["$(c_pePair:%.17g)"] + [f"$(c_virial[{k}]:%.17g)" for k in range(1, 7)]
    if has_bonds:
        totals.append("$(c_peBond:%.17g)")
    lines.append(f'print "{" ".join(totals)}" file totals.txt screen no')
    for name in bond_sets:
        for (other, K, r0), t in bond_types.items():
            lines.append(f"bond_coeff {t} {(K / 2.0 if other == name else 0.0)!r} {r0!r}")
        lines += ["run 0", f'print "$(c_peBond:%.17g)" file bond_{name}.txt screen no']
    return "\n".join(lines) + "\n"


def run_lammps(lmp, positions, box_length, bond_sets):
    bond_types = lammps_bond_types(bond_sets)
    with tempfile.TemporaryDirectory(prefix="structmd-lammps-") as tmp:
        workdir = pathlib.Path(tmp)
        (workdir / "system.data").write_text(lammps_data(positions, box_length, bond_sets, bond_types))
        (workdir / "in.reference").write_text(lammps_script(bond_sets, bond_types))
        run = subprocess.run([lmp, "-in", "in.reference", "-log", "none", "-screen", "screen.txt", "-nocite"],
                             cwd=workdir)
        if run.returncode != 0:
            raise RuntimeError(f"lmp failed:\n{(workdir / 'screen.txt').read_text()[-3000:]}")
        dump = (workdir / "atoms.dump").read_text().splitlines()
        version = subprocess.run([lmp, "-h"], capture_output=True, text=True).stdout.strip().splitlines()[0]
        totals = [float(v) for v in (workdir / "totals.txt").read_text().split()]
        bond_terms = {name: float((workdir / f"bond_{name}.txt").read_text()) for name in bond_sets}
    atoms_header = next(k for k, line in enumerate(dump) if line.startswith("ITEM: ATOMS"))
    table = np.array([[float(v) for v in line.split()] for line in dump[atoms_header + 1:]])
    assert np.array_equal(table[:, 0], np.arange(1, len(positions) + 1)), "dump not sorted by id"
    volume = box_length**3
    pxx, pyy, pzz, pxy, pxz, pyz = totals[1:7]
    virial = volume * np.array([[pxx, pxy, pxz], [pxy, pyy, pyz], [pxz, pyz, pzz]])
    result = {
        "lammps_version": version,
        "forces": table[:, 1:4],
        "particle_energies": table[:, 4],
        "particle_energies_pair": table[:, 5],
        "terms": {"lj": totals[0], **bond_terms},
        "virial": virial,
    }
    if bond_sets:
        result["particle_energies_bond"] = table[:, 6]
    return result


def check_against_numpy(case, lammps, positions, box_length, bond_sets):
    forces, particle_energy, terms, virial = numpy_reference(positions, box_length, bond_sets)
    scale = np.abs(lammps["forces"]).max()
    checks = {
        "forces": np.abs(forces - lammps["forces"]).max() / scale,
        "particle energies": np.abs(particle_energy - lammps["particle_energies"]).max()
                             / np.abs(lammps["particle_energies"]).max(),
        "virial": np.linalg.norm(virial - lammps["virial"]) / np.linalg.norm(lammps["virial"]),
    }
    for name, value in terms.items():
        checks[f"energy {name}"] = abs(value - lammps["terms"][name]) / abs(lammps["terms"][name])
    for what, deviation in checks.items():
        print(f"  {case}: numpy vs LAMMPS {what}: {deviation:.2e}")
        assert deviation < 1e-11, f"{case}: numpy and LAMMPS disagree on {what} ({deviation:.2e})"


def compact_json(document):
    """Top-level keys one per line, long arrays one element per line: small files, readable diffs."""
    items = []
    for key, value in document.items():
        if isinstance(value, list) and len(value) > 9:
            body = ",\n  ".join(json.dumps(row) for row in value)
            items.append(f' {json.dumps(key)}: [\n  {body}]')
        else:
            items.append(f" {json.dumps(key)}: {json.dumps(value)}")
    return "{\n" + ",\n".join(items) + "\n}\n"


def as_lists(x):
    return x.tolist() if isinstance(x, np.ndarray) else x


def write_case(case, lmp, positions, box_length, bond_sets):
    _, r = pair_distances(positions, box_length)
    cutoff = LJ_CUTOFF_FACTOR * LJ_SIGMA
    np.fill_diagonal(r, np.inf)
    assert r.min() >= MIN_DISTANCE
    assert np.abs(r - cutoff).min() > CUTOFF_GUARD, f"{case}: a pair sits on the cutoff"
    assert cutoff * NEIGHBOUR_LIST_FACTOR < 0.5 * box_length
    lammps = run_lammps(lmp, positions, box_length, bond_sets)
    check_against_numpy(case, lammps, positions, box_length, bond_sets)
    potential = sum(lammps["terms"].values())
    reference = {
        "case": case,
        "source": f"LAMMPS ({lammps['lammps_version']}), units lj, serial; written by "
                  "tests/reference/make_lammps_reference.py",
        "num_particles": len(positions),
        "box": [float(box_length)] * 3,
        "energy": {"potential": potential, **lammps["terms"]},
        "virial": as_lists(lammps["virial"]),
        "forces": as_lists(lammps["forces"]),
        "particle_energies": as_lists(lammps["particle_energies"]),
        "particle_energies_pair": as_lists(lammps["particle_energies_pair"]),
    }
    if "particle_energies_bond" in lammps:
        reference["particle_energies_bond"] = as_lists(lammps["particle_energies_bond"])
    DATA_DIR.mkdir(exist_ok=True)
    (DATA_DIR / f"{case}.json").write_text(structmd_input(case, positions, box_length, bond_sets))
    (DATA_DIR / f"{case}.lammps.json").write_text(compact_json(reference))
    print(f"{case}: {len(positions)} particles, L = {box_length:.6f}, U = {potential:.10g}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--lmp", default="lmp", help="LAMMPS executable (default: lmp on PATH)")
    args = parser.parse_args()

    positions, box_length = fcc_liquid_configuration(seed=20240601)
    write_case("lj_liquid", args.lmp, positions, box_length, {})

    positions, box_length = fcc_liquid_configuration(seed=20240602)
    per_bond, common = chain_bonds(len(positions))
    write_case("lj_bonds", args.lmp, positions, box_length, {"bonds": per_bond, "bondsCommon": common})


if __name__ == "__main__":
    main()
