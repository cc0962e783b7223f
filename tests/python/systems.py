"""Small input documents (as dicts) for the Python tests, built fresh on each call so a test may edit
its copy. Geometry is chosen so that nothing overlaps: every non-bonded pair within the LJ cutoff is
about one sigma apart, one of them only through the periodic boundary."""

BASE_BOX = 10.0
BASE_TIME_STEP = 0.002
BASE_POSITIONS = [[0.0, 0.0, 0.0], [1.1, 0.0, 0.0], [4.6, 0.0, -1.0], [-4.4, 0.3, -1.2]]
BASE_VELOCITIES = [[0.1, -0.2, 0.05], [-0.1, 0.1, 0.0], [0.0, 0.05, -0.1], [0.2, 0.0, 0.1]]
BASE_TYPES = ["A", "A", "B", "A"]
TYPE_TABLE = [["A", 1.0, 0.5, 0.0], ["B", 2.0, 0.5, 0.0]]
BOND_K, BOND_R0 = 100.0, 1.0
LJ_CUTOFF_FACTOR = 2.5


def _header(name, box, time_step, types=TYPE_TABLE):
    return {
        "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": name, "seed": 7}}},
        "global": {
            "types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"],
                      "data": [list(row) for row in types]},
            "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"],
                         "data": [[[box, box, box], 1.0]]},
            "fundamental": {"type": ["Fundamental", "Time"], "parameters": {"timeStep": time_step}},
        },
    }


def _schedule(steps, time_step):
    return {
        "vv": {"type": ["Verlet", "VelocityVerlet"], "parameters": {"timeStep": time_step}},
        "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
                     "data": [[1, "vv", steps]]},
    }


def lj_bond_system(steps=1000, box=BASE_BOX, positions=None, velocities=None):
    """Four particles of types A and B: Lennard-Jones between all of them, one harmonic bond 0-1."""
    positions = BASE_POSITIONS if positions is None else positions
    velocities = BASE_VELOCITIES if velocities is None else velocities
    doc = _header("lj-bond", box, BASE_TIME_STEP)
    doc["integrator"] = _schedule(steps, BASE_TIME_STEP)
    doc["state"] = {"labels": ["id", "position", "velocity"],
                    "data": [[i, list(p), list(v)] for i, (p, v) in enumerate(zip(positions, velocities))]}
    doc["topology"] = {
        "structure": {"labels": ["id", "type"], "data": [[i, t] for i, t in enumerate(BASE_TYPES)]},
        "forceField": {
            "nl": {"type": ["VerletConditionalListSet", "all"], "parameters": {"cutOffVerletFactor": 1.2}},
            "lj": {"type": ["NonBonded", "LennardJonesType1"],
                   "parameters": {"cutOffFactor": LJ_CUTOFF_FACTOR, "condition": "all"},
                   "labels": ["name_i", "name_j", "epsilon", "sigma"],
                   "data": [["A", "A", 1.0, 1.0], ["A", "B", 1.0, 1.0], ["B", "B", 1.0, 1.0]]},
            "bonds": {"type": ["Bond2", "Harmonic"], "labels": ["id_i", "id_j", "K", "r0"],
                      "data": [[0, 1, BOND_K, BOND_R0]]},
        },
    }
    return doc


def dimer_system(separation=1.3, box=8.0, steps=1000, bond=("Harmonic", ["K", "r0"], [BOND_K, BOND_R0])):
    """Two particles of type A joined by one bond (harmonic by default) and nothing else; particle 0 at
    the origin, particle 1 along a direction with all three components non-zero."""
    subclass, labels, values = bond
    direction = [0.48, -0.6, 0.64]  # unit vector
    doc = _header("dimer", box, BASE_TIME_STEP, types=[TYPE_TABLE[0]])
    doc["integrator"] = _schedule(steps, BASE_TIME_STEP)
    doc["state"] = {"labels": ["id", "position", "velocity"],
                    "data": [[0, [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]],
                             [1, [separation * c for c in direction], [0.0, 0.0, 0.0]]]}
    doc["topology"] = {
        "structure": {"labels": ["id", "type"], "data": [[0, "A"], [1, "A"]]},
        "forceField": {"bond": {"type": ["Bond2", subclass], "labels": ["id_i", "id_j", *labels],
                                "data": [[0, 1, *values]]}},
    }
    return doc


# Lennard-Jones argon for the ASE and i-PI tests: Å and eV, ASE's LennardJones conventions.
SIGMA, EPSILON = 3.405, 0.010318
CUTOFF_FACTOR = 3.0  # ASE's default rc = 3 sigma
LATTICE = 5.26  # Å; 4 cubic cells give a 21.04 Å box, more than twice rc (10.2 Å)


def rattled_argon(seed):
    """256 argon atoms of an fcc crystal (ase.Atoms), each moved at random by about 0.08 Å."""
    from ase.build import bulk

    atoms = bulk("Ar", "fcc", a=LATTICE, cubic=True).repeat(4)
    atoms.rattle(stdev=0.08, seed=seed)
    return atoms


def lj_input(atoms, sigma=SIGMA, epsilon=EPSILON, length_unit=1.0):
    """The structmd input of ASE's LennardJones(sigma, epsilon, rc=3 sigma): shifted at the cutoff."""
    box = [atoms.cell[k, k] / length_unit for k in range(3)]
    positions = atoms.positions / length_unit
    return {
        "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": "ase-lj", "seed": 1}}},
        "global": {
            "types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"],
                      "data": [["Ar", 39.948, 0.5 * sigma, 0.0]]},
            "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"], "data": [[box, 0.0]]},
        },
        "state": {"labels": ["id", "position"], "data": [[i, list(p)] for i, p in enumerate(positions.tolist())]},
        "topology": {
            "structure": {"labels": ["id", "type"], "data": [[i, "Ar"] for i in range(len(atoms))]},
            "forceField": {
                "nl": {"type": ["VerletConditionalListSet", "all"], "parameters": {"cutOffVerletFactor": 1.02}},
                "lj": {"type": ["NonBonded", "LennardJonesType1"],
                       "parameters": {"cutOffFactor": CUTOFF_FACTOR, "condition": "all", "shift": True},
                       "labels": ["name_i", "name_j", "epsilon", "sigma"], "data": [["Ar", "Ar", epsilon, sigma]]},
            },
        },
    }
