"""Every force-field component through the whole engine (reader, kernels, neighbour list, energy
split): the force on each particle equals minus the central finite difference of the potential
energy, in double precision, on a random non-degenerate configuration that straddles the periodic
boundary. The functor tests check the formulas; this checks the plumbing around them."""

import math
import zlib

import numpy as np
import pytest

import structmd

BOX = 7.0
N = 12


def configuration(seed):
    """N particles, each at least 0.85 from the others (minimum image), clustered around a box face
    so that many pairs and bonds cross the boundary."""
    rng = np.random.default_rng(seed)
    positions = []
    while len(positions) < N:
        candidate = rng.uniform(-1.6, 1.6, 3)
        candidate[0] += BOX / 2  # around x = +-L/2
        candidate -= BOX * np.round(candidate / BOX)
        if all(np.linalg.norm((candidate - p) - BOX * np.round((candidate - p) / BOX)) > 0.85 for p in positions):
            positions.append(candidate)
    return np.array(positions)


def document(positions, force_field, charges=None):
    state_labels = ["id", "position", "velocity"] + (["charge"] if charges is not None else [])
    rows = []
    for i, p in enumerate(positions):
        row = [i, list(p), [0.0, 0.0, 0.0]]
        if charges is not None:
            row.append(charges[i])
        rows.append(row)
    return {
        "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": "gradients"}}},
        "global": {
            "units": {"type": ["Units", "KcalMol_A"]},
            "types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"],
                      "data": [["A", 1.0, 0.3, 0.0], ["B", 2.0, 0.4, 0.0]]},
            "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"],
                         "data": [[[BOX, BOX, BOX], 300.0]]},
        },
        "integrator": {
            "vv": {"type": ["Verlet", "VelocityVerlet"], "parameters": {"timeStep": 0.001}},
            "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
                         "data": [[1, "vv", 10]]},
        },
        "state": {"labels": state_labels, "data": rows},
        "topology": {"structure": {"labels": ["id", "type"],
                                   "data": [[i, "A" if i % 3 else "B"] for i in range(len(positions))]},
                     "forceField": force_field},
    }


TABLE = [["A", "A", 0.8, 1.0], ["A", "B", 1.2, 0.9], ["B", "B", 0.6, 1.1]]
NEGATIVE = [["A", "A", -0.8, 1.0], ["A", "B", 1.2, 0.9], ["B", "B", -0.6, 1.1]]
NL = {"type": ["VerletConditionalListSet", "all"], "parameters": {"cutOffVerletFactor": 1.15}}


def pair(subclass, table=TABLE, shift=False):
    return {"nl": NL, "term": {"type": ["NonBonded", subclass],
                               "parameters": {"cutOffFactor": 2.4, "condition": "all", "shift": shift},
                               "labels": ["name_i", "name_j", "epsilon", "sigma"], "data": table}}


# Surface walls: per type (epsilon, sigma); the planes keep 0.4 or more from the particles (|z| <= 1.6), and
# the WCA ones (WIDE: reaching 1.6 from their plane) act on some of them.
TYPE_TABLE = [["A", 0.8, 0.9], ["B", 1.2, 0.8]]
WIDE_TABLE = [["A", 0.8, 1.5], ["B", 1.2, 1.4]]
WIDE_NEGATIVE = [["A", -0.8, 1.5], ["B", 1.2, 1.4]]


# A cube of half-edge 1.2 about the origin, as 12 triangles; the particles (|x| >= 1.9) are outside it.
CUBE = {"vertex": [[x, y, z] for z in (-1.2, 1.2) for y in (-1.2, 1.2) for x in (-1.2, 1.2)],
        "faces": [f for a, b, c, d in [(0, 1, 3, 2), (4, 5, 7, 6), (0, 1, 5, 4), (2, 3, 7, 6), (0, 2, 6, 4),
                                       (1, 3, 7, 5)] for f in ([a, b, c], [a, d, c])]}


def surface(subclass, parameters, table):
    return {"term": {"type": ["Surface", subclass], "parameters": parameters,
                     "labels": ["name", "epsilon", "sigma"], "data": table}}


def soft_pair(subclass, shift=False):
    entry = pair(subclass, shift=shift)
    entry["term"]["parameters"].update({"alpha": 0.5, "n": 3})
    return entry


# The terms of lambda (test_lambda.py) run at this lambda (["Ensemble","NVTlambda"]).
LAMBDA = 0.6


def with_parameters(case, parameters):
    case["term"]["parameters"] = parameters
    return case


def chain(ids, arity):
    return [ids[k:k + arity] for k in range(0, len(ids) - arity + 1)]


def bonds(cls, subclass, arity, labels, values):
    rows = [list(ids) + list(values(k)) for k, ids in enumerate(chain(list(range(N)), arity))]
    id_labels = ["id_i", "id_j", "id_k", "id_l"][:arity]
    return {"term": {"type": [cls, subclass], "labels": id_labels + labels, "data": rows}}


# Terms on centres of mass (Set1, Set2): sets of mixed masses (types A and B) that straddle the boundary.
SETS1 = [[0, 1, 2, 3], [4, 5, 6], [7, 8, 9, 10, 11]]
SETS2 = [[[0, 1, 2], [3, 4, 5]], [[6, 7], [8, 9, 10, 11]]]
SET_CASES = [
    ("Set1 FixedHarmonicAnisotropicCenterOfMass", [[s] for s in SETS1], ["idSet_i", "K", "r0", "position"],
     lambda k: [[3.0, 5.0, 2.0], [0.4, 0.1, 0.3], [3.3, 0.4 * k - 1.0, 0.5]], None),
    ("Set1 FixedHarmonicAnisotropicCommon_K_r0CenterOfMass", [[s] for s in SETS1], ["idSet_i", "position"],
     lambda k: [[3.3, 0.4 * k - 1.0, 0.5]], {"K": 4.0, "r0": 0.3}),
    ("Set2 HarmonicBondBetweenCentersOfMass", SETS2, ["idSet_i", "idSet_j", "K", "r0"],
     lambda k: [10.0 + k, 0.8], None),
    ("Set2 ConstantForceBetweenCentersOfMass", SETS2, ["idSet_i", "idSet_j", "force"], lambda k: [1.5 - 2.0 * k], None),
]


def sets(name, rows, labels, values, parameters):
    term = {"type": name.split(" "), "labels": labels,
            "data": [list(row) + list(values(k)) for k, row in enumerate(rows)]}
    if parameters:
        term["parameters"] = parameters
    return {"term": term}


CASES = {
    **{name: pair(name) for name in ["LennardJonesType1", "LennardJonesType2", "LennardJonesType3", "WCAType1",
                                     "WCAType2", "WCAType3", "Steric6", "Steric12"]},
    "LennardJonesType1 shifted": pair("LennardJonesType1", shift=True),
    **{f"GeneralLennardJonesType{k}": pair(f"GeneralLennardJonesType{k}", NEGATIVE) for k in (1, 2, 3)},
    "DebyeHuckel": {"nl": NL, "term": {"type": ["NonBonded", "DebyeHuckel"],
                                       "parameters": {"cutOffFactor": 2.0, "condition": "all",
                                                      "dielectricConstant": 80.0, "debyeLength": 1.5}}},
    "SplitLennardJones": {"nl": NL, "term": {"type": ["NonBonded", "SplitLennardJones"],
                                             "parameters": {"cutOffFactor": 2.4, "condition": "all",
                                                            "epsilon_r": 1.5, "epsilon_a": 0.7},
                                             "labels": ["name_i", "name_j", "epsilon", "sigma"], "data": TABLE}},
    "LaTorre": {"nl": NL, "term": {"type": ["NonBonded", "LaTorre"], "parameters": {"condition": "all"},
                                   "labels": ["name_i", "name_j", "epsilon", "sigma", "w"],
                                   "data": [["A", "A", 0.8, 0.9, 1.0], ["A", "B", 1.2, 0.8, 0.9],
                                            ["B", "B", 0.6, 1.0, 1.2]]}},
    "Clashed": {"nl": NL, "term": {"type": ["NonBonded", "Clashed"],
                                   "parameters": {"condition": "all", "lambda": 2.0, "gamma": 1.5}}},
    **{f"DLVOType{k}": {"nl": NL, "term": {"type": ["NonBonded", f"DLVOType{k}"],
                                           "parameters": {"cutOffNPFactor": 2.4, "cutOffDHFactor": 2.0,
                                                          "dielectricConstant": 80.0, "debyeLength": 1.5,
                                                          "condition": "all", "shift": k == 2},
                                           "labels": ["name_i", "name_j", "epsilon", "sigma"],
                                           "data": TABLE[:2]}} for k in (1, 2, 3)},
    "KimHummer": {"nl": NL, "term": {"type": ["NonBonded", "KimHummer"],
                                     "parameters": {"cutOffNPFactor": 2.4, "cutOffDHFactor": 2.0,
                                                    "dielectricConstant": 80.0, "debyeLength": 1.5,
                                                    "zeroEnergy": 0.3, "condition": "all"},
                                     "labels": ["name_i", "name_j", "epsilon", "sigma"],
                                     "data": [["A", "A", -0.8, 1.0], ["A", "B", 1.2, 0.9], ["B", "B", 0.0, 1.1]]}},
    "Bond1 FixedHarmonic": bonds("Bond1", "FixedHarmonic", 1, ["K", "r0", "position"],
                                 lambda k: [3.0, 0.4, [3.3, 0.2 * k - 1.0, 0.5]]),
    "Bond1 FixedHarmonicAnisotropic": bonds("Bond1", "FixedHarmonicAnisotropic", 1, ["K", "r0", "position"],
                                            lambda k: [[3.0, 5.0, 2.0], [0.4, 0.1, 0.3], [3.3, 0.2 * k - 1.0, 0.5]]),
    "Bond2 Harmonic": bonds("Bond2", "Harmonic", 2, ["K", "r0"], lambda k: [10.0 + k, 1.0]),
    "Bond2 MaxDistanceRestraint": bonds("Bond2", "MaxDistanceRestraint", 2, ["K", "maxDistance"],
                                        lambda k: [10.0 + k, 0.5 + 0.1 * k]),
    "Bond2 HarmonicAnisotropic": bonds("Bond2", "HarmonicAnisotropic", 2, ["K", "r0"],
                                       lambda k: [[10.0, 5.0, 8.0], [0.5, 0.2, 0.4]]),
    "Bond2 Fene": bonds("Bond2", "Fene", 2, ["r0", "K", "R0"], lambda k: [0.3, 5.0, 6.0]),
    "Bond2 Morse": bonds("Bond2", "Morse", 2, ["r0", "E", "D"], lambda k: [1.0, 2.0, 0.7]),
    "Bond2 LennardJonesType2": bonds("Bond2", "LennardJonesType2", 2, ["epsilon", "sigma"], lambda k: [0.5, 0.8]),
    "Bond2 Gaussian": bonds("Bond2", "Gaussian", 2, ["E", "r0", "D"], lambda k: [1.5, 1.2, 0.8]),
    "Bond2 LennardJonesKaranicolasBrooks": bonds("Bond2", "LennardJonesKaranicolasBrooks", 2, ["epsilon", "sigma"],
                                                 lambda k: [0.5, 0.9 + 0.05 * k]),
    "Bond2 LennardJonesGaussian": bonds("Bond2", "LennardJonesGaussian", 2, ["epsilon", "sigma", "D"],
                                        lambda k: [0.7, 1.0 + 0.1 * (k % 5), 0.3]),
    "Bond2 MorseWCACommon_eps0": {"term": dict(bonds("Bond2", "MorseWCACommon_eps0", 2, ["r0", "E", "D"],
                                                     lambda k: [1.0 + 0.1 * (k % 5), 2.0, 0.7])["term"],
                                               parameters={"eps0": 1.5})},
    "Bond2 Steric12": bonds("Bond2", "Steric12", 2, ["epsilon", "sigma"], lambda k: [0.5, 0.8]),
    "Bond2 DebyeHuckel": bonds("Bond2", "DebyeHuckel", 2, ["chgProduct", "dielectricConstant", "debyeLength",
                                                            "cutOff"], lambda k: [-0.5, 40.0, 2.0, 3.4]),
    "Bond3 HarmonicAngular": bonds("Bond3", "HarmonicAngular", 3, ["K", "theta0"], lambda k: [4.0, 2.0]),
    "Bond3 KratkyPorod": bonds("Bond3", "KratkyPorod", 3, ["K"], lambda k: [3.0]),
    "Bond3 BestChenHummerAngular": bonds("Bond3", "BestChenHummerAngular", 3, [], lambda k: []),
    "Bond4 Dihedral": bonds("Bond4", "Dihedral", 4, ["n", "K", "phi0"], lambda k: [1 + k % 3, 2.0, 0.4]),
    "Bond4 Dihedral4": bonds("Bond4", "Dihedral4", 4, ["K", "phi0"],
                             lambda k: [[1.0, 0.5, 0.2, 0.1], [0.1, 0.2, 0.3, 0.4]]),
    "Bond4 IDP_Fourier": bonds("Bond4", "IDP_Fourier", 4, [], lambda k: []),
    **{f"NonBonded {name}": soft_pair(name) for name in ["Steric6SoftCore", "Steric12SoftCore",
                                                          "LennardJonesSoftCoreType1", "LennardJonesSoftCoreType2"]},
    "NonBonded LennardJonesSoftCoreType2 shifted": soft_pair("LennardJonesSoftCoreType2", shift=True),
    "Bond2 LambdaHarmonic": with_parameters(bonds("Bond2", "LambdaHarmonic", 2, ["K", "r0"], lambda k: [10.0 + k, 1.0]),
                                            {"n": 3}),
    "Bond1 LambdaFixedHarmonicAnisotropic": with_parameters(
        bonds("Bond1", "LambdaFixedHarmonicAnisotropic", 1, ["K", "r0", "position"],
              lambda k: [[3.0, 5.0, 2.0], [0.4, 0.1, 0.3], [3.3, 0.2 * k - 1.0, 0.5]]), {"n": 2}),
    "Bond2 LennardJonesSoftCoreType1": with_parameters(
        bonds("Bond2", "LennardJonesSoftCoreType1", 2, ["epsilon", "sigma"], lambda k: [0.5, 0.8]),
        {"alpha": 0.4, "n": 2}),
    "Bond2 LennardJonesSoftCoreType2Common_epsilon": with_parameters(
        bonds("Bond2", "LennardJonesSoftCoreType2Common_epsilon", 2, ["sigma"], lambda k: [0.8 + 0.02 * k]),
        {"epsilon": 0.7, "alpha": 0.4, "n": 1}),
    "External Plates": {"term": {"type": ["External", "Plates"],
                                 "parameters": {"platesSeparation": 6.0, "platesEpsilon": 0.5}}},
    "External SphericalShell": {"term": {"type": ["External", "SphericalShell"],
                                         "parameters": {"shellCenter": [3.5, 0.0, 0.0], "shellRadius": 4.0}}},
    **{f"Surface {name}": surface(name, {"surfacePosition": plane}, table)
       for name, plane, table in [("SurfaceLennardJonesType1", 2.5, TYPE_TABLE),
                                  ("SurfaceLennardJonesType2", 2.5, TYPE_TABLE),
                                  ("SurfaceWCAType1", 2.2, WIDE_TABLE), ("SurfaceWCAType2", 2.2, WIDE_TABLE),
                                  ("SurfaceGeneralLennardJonesType1", 2.2, WIDE_NEGATIVE),
                                  ("SurfaceGeneralLennardJonesType2", 2.2, WIDE_NEGATIVE),
                                  ("SurfaceIntegratedLennardJonesType2", 2.5, TYPE_TABLE)]},
    "Surface SurfaceAnchorage": surface("SurfaceAnchorage", {"surfacePosition": 0.5},
                                        [["A", 3.0, 1.2], ["B", 2.0, 0.9]]),
    "Surface ParabolaSurface": surface("ParabolaSurface", {"surfacePosition": 0.2},
                                       [["A", 4.0, 1.0], ["B", 2.5, 1.0]]),
    "Surface WCA_PlainCylinder": surface("WCA_PlainCylinder", {"plainPosition": -2.0, "cylinderRadius": 3.0},
                                         [["A", 1.0, 0.9], ["B", 0.7, 1.0]]),
    "Surface WCA_Polyhedron": surface("WCA_Polyhedron", CUBE, [["A", 1.0, 1.5], ["B", 0.7, 1.4]]),
    **{case[0]: sets(*case) for case in SET_CASES},
}


def case_document(name):
    """The configuration of case `name` (its own seed) and its input, with charges where the term reads them."""
    # Seeded by the name alone, so that adding a case moves no other case's configuration.
    positions = configuration(seed=zlib.crc32(name.encode()))
    charged = any(word in name for word in ("DebyeHuckel", "DLVO", "KimHummer"))
    charges = list(np.linspace(-1.0, 1.0, N)) if charged else None
    doc = document(positions, CASES[name], charges)
    if "SoftCore" in name or "Lambda" in name:
        doc["global"]["ensemble"] = {"type": ["Ensemble", "NVTlambda"], "labels": ["box", "temperature", "lambda"],
                                     "data": [[[BOX, BOX, BOX], 300.0, LAMBDA]]}
    return positions, doc


@pytest.mark.parametrize("name", sorted(CASES))
def test_force_is_minus_the_energy_gradient(options, name):
    positions, doc = case_document(name)
    with structmd.Simulation(dict(options, precision="double")) as sim:
        sim.load(doc)
        forces = sim.forces
        assert np.all(np.isfinite(forces))
        assert np.max(np.abs(forces)) > 0.0, "the term must act on this configuration"
        h = 1e-5
        numerical = np.zeros_like(forces)
        for i in range(N):
            for d in range(3):
                moved = positions.copy()
                moved[i, d] += h
                sim.positions = moved
                up = sim.energy("term")
                moved[i, d] -= 2 * h
                sim.positions = moved
                down = sim.energy("term")
                numerical[i, d] = -(up - down) / (2 * h)
        error = np.max(np.abs(forces - numerical)) / np.max(np.abs(numerical))
        assert error < 1e-6, f"{name}: relative error {error:.2e}"
