"""Patchy particles: ["PatchyParticles","PatchyParticles"] and ["PatchyParticles","DynamicallyBondedPatchyParticles"]
with their patch terms ["NonBondedPatches","DistanceSwitchCosine"], ["NonBondedPatches","COSRAP"] and
["SurfacePatches","Linker"]. Energies against the formulas written here from UAMMD-structured's
description; forces and torques against central differences of the energy (a torque by turning the
parent's quaternion by a small angle about each lab axis: tau = -dE/dtheta); the cutoff; the rule of
the dynamic bonds (a patch bonds to one partner at most); and ["WriteStep","WritePatchyParticlesStep"]
read back."""

import math
import os

import numpy as np
import pytest

import structmd

BOX = 6.0
TYPES = [["A", 1.0, 0.5, 0.0]]
PATCH_TYPES = [["S", 0.0, 0.1, 0.0], ["E", 0.0, 0.2, 0.0]]
H = 1e-5  # finite-difference step in length and angle


def rotation_matrix(q):
    """Body axes as columns, q = [q0, q1, q2, q3] scalar first (UAMMD-structured's State)."""
    q0, q1, q2, q3 = q
    return np.array([[1 - 2 * q2 * q2 - 2 * q3 * q3, 2 * q1 * q2 - 2 * q0 * q3, 2 * q1 * q3 + 2 * q0 * q2],
                     [2 * q1 * q2 + 2 * q0 * q3, 1 - 2 * q1 * q1 - 2 * q3 * q3, 2 * q2 * q3 - 2 * q0 * q1],
                     [2 * q1 * q3 - 2 * q0 * q2, 2 * q2 * q3 + 2 * q0 * q1, 1 - 2 * q1 * q1 - 2 * q2 * q2]])


def turned(q, axis, angle):
    """q after turning its body by angle about the lab axis: (cos(a/2); sin(a/2) k) * q."""
    k = np.zeros(3)
    k[axis] = 1.0
    a, v = math.cos(angle / 2), math.sin(angle / 2) * k
    q0, qv = q[0], np.asarray(q[1:])
    return np.concatenate([[a * q0 - v @ qv], a * qv + q0 * v + np.cross(v, qv)])


def minimum_image(d):
    return d - BOX * np.round(d / BOX)


def mask(x, K):
    return x / (x + K * (1 - x))


def cosine_switch(r, rc, K):
    return mask(0.5 * (1 + np.cos(np.pi * r / rc)), K) if r <= rc else 0.0


def cosine_energy(r, p):
    return -p["E"] * cosine_switch(r, p["rc"], p["K"])


def cosrap_energy(r, A, B, p):
    if r > p["rc"]:
        return 0.0
    R = rotation_matrix(p["R"])
    orientation = (1 + np.trace((A.T @ B).T @ R)) / 4
    return -p["E"] * cosine_switch(r, p["rc"], p["Kswt"]) * mask(orientation, p["Krap"])


def linker_energy(z, p):
    return -p["epsilon"] * math.exp(-(z - p["surface"]) ** 2 / (2 * p["sigma"]))


def patch_sites(positions, directions, patches):
    """patches: [(parent, type, offset)] -> sites, the parents' rotation matrices."""
    rotations = [rotation_matrix(q) for q in directions]
    sites = [np.asarray(positions[p]) + rotations[p] @ np.asarray(o) for p, _, o in patches]
    return np.array(sites), rotations


def reference_energy(positions, directions, patches, cosine=None, cosrap=None, linker=None, inter_only=False):
    """The total energy by summing every patch pair once (cosine: {(ti, tj): params}; cosrap the same,
    with R for (ti, tj); linker: {type: params})."""
    sites, rotations = patch_sites(positions, directions, patches)
    total = 0.0
    for a, (pa, ta, _) in enumerate(patches):
        if linker and ta in linker:
            total += linker_energy(sites[a][2], linker[ta])
        for b in range(a + 1, len(patches)):
            pb, tb, _ = patches[b]
            if inter_only and pa == pb:
                continue
            r = np.linalg.norm(minimum_image(sites[b] - sites[a]))
            if cosine and (ta, tb) in cosine:
                total += cosine_energy(r, cosine[(ta, tb)])
            if cosrap and (ta, tb) in cosrap:
                total += cosrap_energy(r, rotations[pa], rotations[pb], cosrap[(ta, tb)])
    return total


# ---- documents ------------------------------------------------------------------------------------

def patchy_entry(patches, terms, dynamic=False, threshold=0.0, list_type="all", verlet_factor=1.2):
    """patches: [(parent, type name, offset)]; terms: the patches' force-field entries."""
    force_field = dict(terms)
    if any(t["type"][0] == "NonBondedPatches" for t in terms.values()):
        force_field["patchList"] = {"type": ["VerletConditionalListSet", list_type],
                                    "parameters": {"cutOffVerletFactor": verlet_factor}}
    return {
        "type": ["PatchyParticles", "DynamicallyBondedPatchyParticles" if dynamic else "PatchyParticles"],
        "patchesState": {"labels": ["id", "position"], "data": [[k, list(o)] for k, (_, _, o) in enumerate(patches)]},
        "patchesGlobal": {
            "fundamental": {"type": ["Fundamental", "DynamicallyBondedPatchyParticles"],
                            "parameters": {"energyThreshold": threshold}},
            "types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"], "data": PATCH_TYPES},
        },
        "patchesTopology": {
            "structure": {"labels": ["id", "type", "parentId"], "data": [[k, t, p] for k, (p, t, _) in enumerate(patches)]},
            "forceField": force_field,
        },
    }


def document(positions, directions, entry, steps_section=None):
    doc = {
        "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": "patchy", "seed": 3}}},
        "global": {
            "types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"], "data": TYPES},
            "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"], "data": [[[BOX] * 3, 1.0]]},
        },
        "state": {"labels": ["id", "position", "direction"],
                  "data": [[i, list(map(float, x)), list(map(float, q))] for i, (x, q) in enumerate(zip(positions, directions))]},
        "topology": {"structure": {"labels": ["id", "type"], "data": [[i, "A"] for i in range(len(positions))]},
                     "forceField": {"patchy": entry}},
    }
    if steps_section:
        doc["simulationStep"] = steps_section
    return doc


def cosine_term(rows, condition="all"):
    return {"type": ["NonBondedPatches", "DistanceSwitchCosine"], "parameters": {"condition": condition},
            "labels": ["name_i", "name_j", "E", "K", "rc"], "data": rows}


def cosrap_term(rows, condition="inter"):
    return {"type": ["NonBondedPatches", "COSRAP"], "parameters": {"condition": condition},
            "labels": ["name_i", "name_j", "E", "Kswt", "Krap", "rc", "R"], "data": rows}


def linker_term(rows, surface=0.0):
    return {"type": ["SurfacePatches", "Linker"], "parameters": {"surfacePosition": surface},
            "labels": ["name", "epsilon", "sigma"], "data": rows}


def random_quaternions(n, seed):
    q = np.random.default_rng(seed).normal(size=(n, 4))
    return q / np.linalg.norm(q, axis=1)[:, None]


# Three particles, particle 2 across the periodic boundary from particle 0; each with an S and an E patch.
POSITIONS = np.array([[2.55, 0.1, -0.2], [1.7, 0.6, 0.3], [-2.75, -0.3, 0.25]])
OFFSETS = {"S": [0.45, 0.0, 0.0], "E": [-0.1, 0.42, 0.05]}
PATCHES = [(i, t, OFFSETS[t]) for i in range(3) for t in ("S", "E")]
COSINE = {"E": 8.0, "K": 2.5, "rc": 1.2}
R_SE = np.array([0.2, -0.4, 0.3, 0.6])
R_SE = R_SE / np.linalg.norm(R_SE)
R_ES = R_SE * np.array([1, -1, -1, -1])
COSRAP_SE = {"E": 10.0, "Kswt": 3.0, "Krap": 1.5, "rc": 1.3, "R": R_SE}
COSRAP_ES = dict(COSRAP_SE, R=R_ES)
LINKER = {"epsilon": 5.0, "sigma": 0.7, "surface": 0.1}


def cosine_case():
    entry = patchy_entry(PATCHES, {"cosine": cosine_term([["S", "S", COSINE["E"], COSINE["K"], COSINE["rc"]],
                                                          ["S", "E", COSINE["E"], COSINE["K"], COSINE["rc"]],
                                                          ["E", "E", COSINE["E"], COSINE["K"], COSINE["rc"]]])})
    reference = dict(cosine={(a, b): COSINE for a in "SE" for b in "SE"})
    return entry, reference


def cosrap_case():
    rows = [["S", "E", COSRAP_SE["E"], COSRAP_SE["Kswt"], COSRAP_SE["Krap"], COSRAP_SE["rc"], list(R_SE)],
            ["E", "S", COSRAP_SE["E"], COSRAP_SE["Kswt"], COSRAP_SE["Krap"], COSRAP_SE["rc"], list(R_ES)]]
    entry = patchy_entry(PATCHES, {"cosrap": cosrap_term(rows)}, list_type="interDifferentType")
    reference = dict(cosrap={("S", "E"): COSRAP_SE, ("E", "S"): COSRAP_ES}, inter_only=True)
    return entry, reference


def linker_case():
    entry = patchy_entry(PATCHES, {"linker": linker_term([["S", LINKER["epsilon"], LINKER["sigma"]]],
                                                         surface=LINKER["surface"])})
    return entry, dict(linker={"S": LINKER})


def combined_case():
    rows = [["S", "E", COSRAP_SE["E"], COSRAP_SE["Kswt"], COSRAP_SE["Krap"], COSRAP_SE["rc"], list(R_SE)]]
    entry = patchy_entry(PATCHES, {"cosine": cosine_term([["S", "S", COSINE["E"], COSINE["K"], COSINE["rc"]]], "inter"),
                                   "cosrap": cosrap_term(rows),
                                   "linker": linker_term([["E", LINKER["epsilon"], LINKER["sigma"]]], LINKER["surface"])},
                         list_type="intra_inter")
    reference = dict(cosine={("S", "S"): COSINE}, cosrap={("S", "E"): COSRAP_SE, ("E", "S"): COSRAP_ES},
                     linker={"E": LINKER}, inter_only=True)
    return entry, reference


CASES = {"cosine": cosine_case, "cosrap": cosrap_case, "linker": linker_case, "combined": combined_case}


@pytest.fixture(params=list(CASES))
def case(request):
    return CASES[request.param]()


def loaded(options, entry, directions, positions=POSITIONS, steps_section=None):
    sim = structmd.Simulation(options)
    sim.load(document(positions, directions, entry, steps_section))
    return sim


def test_energy_matches_the_formulas(case, options):
    entry, reference = case
    directions = random_quaternions(3, 11)
    with loaded(options, entry, directions) as sim:
        energy = sim.energy()
        per_particle = np.array(sim.particle_energies)
    expected = reference_energy(POSITIONS, directions, PATCHES, **reference)
    assert expected < -0.2  # the geometry puts several pairs inside their cutoff
    assert energy == pytest.approx(expected, rel=1e-10, abs=1e-12)
    assert per_particle.sum() == pytest.approx(expected, rel=1e-10, abs=1e-12)


def test_forces_and_torques_are_derivatives(case, options):
    entry, _ = case
    directions = random_quaternions(3, 5)
    with loaded(options, entry, directions) as sim:
        forces = np.array(sim.forces, copy=True)
        torques = np.array(sim.torques, copy=True)
        assert np.abs(forces).max() > 0.1 and np.abs(torques).max() > 0.1
        for i in range(3):
            for axis in range(3):
                energies = []
                for sign in (1, -1):
                    moved = POSITIONS.copy()
                    moved[i, axis] += sign * H
                    sim.positions = moved
                    energies.append(sim.energy())
                sim.positions = POSITIONS
                fd = -(energies[0] - energies[1]) / (2 * H)
                assert forces[i, axis] == pytest.approx(fd, rel=1e-6, abs=1e-7), (i, axis)
                energies = []
                for sign in (1, -1):
                    turned_directions = directions.copy()
                    turned_directions[i] = turned(directions[i], axis, sign * H)
                    sim.orientations = turned_directions
                    energies.append(sim.energy())
                sim.orientations = directions
                fd = -(energies[0] - energies[1]) / (2 * H)
                assert torques[i, axis] == pytest.approx(fd, rel=1e-6, abs=1e-7), (i, axis)


def test_patches_beyond_the_cutoff_do_not_interact(options):
    patches = [(i, t, OFFSETS[t]) for i in range(2) for t in ("S", "E")]
    rows = [["S", "E", COSRAP_SE["E"], COSRAP_SE["Kswt"], COSRAP_SE["Krap"], COSRAP_SE["rc"], list(R_SE)]]
    entry = patchy_entry(patches, {"cosrap": cosrap_term(rows)}, list_type="interDifferentType")
    directions = random_quaternions(2, 2)
    # Offsets are under 0.46 long: the patches of parents 2.8 apart are over 1.3 (rc) apart.
    positions = np.array([[0.0, 0.0, 0.0], [2.8, 0.3, 0.0]])
    with loaded(options, entry, directions, positions=positions) as sim:
        assert sim.energy() == 0.0
        assert np.all(np.array(sim.forces) == 0.0)
        assert np.all(np.array(sim.torques) == 0.0)
        # Just inside: S of particle 0 and E of particle 1 moved to rc - 1e-3 apart.
        sites, _ = patch_sites(positions, directions, patches)
        gap = sites[3] - sites[0]
        moved = positions.copy()
        moved[1] -= gap * (1 - (COSRAP_SE["rc"] - 1e-3) / np.linalg.norm(gap))
        sim.positions = moved
        assert sim.energy() < 0.0


# ---- dynamic bonds --------------------------------------------------------------------------------

def bonding_system(dynamic):
    """Particle 0's patch faces those of particles 1 (nearer) and 2, which face it: three free patches
    within each other's reach, which a dynamic bond pairs two at a time."""
    positions = np.array([[0.0, 0.0, 0.0], [1.3, 0.2, 0.0], [1.3, -0.3, 0.0]])
    directions = np.array([[1.0, 0, 0, 0], [0, 0, 0, 1.0], [0, 0, 0, 1.0]])  # 1 and 2 turned by pi about z
    patches = [(0, "S", [0.5, 0.0, 0.0]), (1, "S", [0.5, 0.0, 0.0]), (2, "S", [0.5, 0.0, 0.0])]
    entry = patchy_entry(patches, {"cosine": cosine_term([["S", "S", 10.0, 2.0, 0.6]], "inter")},
                         dynamic=dynamic, list_type="intra_inter")
    return positions, directions, patches, entry


def pair_energy(positions, directions, patches, a, b):
    sites, _ = patch_sites(positions, directions, patches)
    return cosine_energy(np.linalg.norm(sites[b] - sites[a]), {"E": 10.0, "K": 2.0, "rc": 0.6})


def test_plain_patches_interact_with_every_partner(options):
    positions, directions, patches, entry = bonding_system(dynamic=False)
    e01 = pair_energy(positions, directions, patches, 0, 1)
    e02 = pair_energy(positions, directions, patches, 0, 2)
    e12 = pair_energy(positions, directions, patches, 1, 2)
    assert e01 < e02 < 0.0 and e12 < 0.0
    with loaded(options, entry, directions, positions) as sim:
        assert sim.energy() == pytest.approx(e01 + e02 + e12, rel=1e-12)
        sim.positions = positions  # another configuration changes nothing
        assert sim.energy() == pytest.approx(e01 + e02 + e12, rel=1e-12)


def test_a_dynamic_bond_takes_one_partner(options):
    positions, directions, patches, entry = bonding_system(dynamic=True)
    e01 = pair_energy(positions, directions, patches, 0, 1)
    e02 = pair_energy(positions, directions, patches, 0, 2)
    e12 = pair_energy(positions, directions, patches, 1, 2)
    # Patch 1's lowest pair is with patch 0 only if e01 < e12: then 0 and 1 choose each other.
    assert e01 < e12 < 0.0 and e01 < e02 < 0.0
    with loaded(options, entry, directions, positions) as sim:
        # The first configuration has no bonds yet: every pair interacts.
        assert sim.energy() == pytest.approx(e01 + e02 + e12, rel=1e-12)
        # The next one bonds 0 and 1, who chose each other; 2 (which chose 0) stays free and meets no
        # free partner: only the bond acts, and on 0 and 1 alone.
        sim.positions = positions
        assert sim.energy() == pytest.approx(e01, rel=1e-12)
        per_particle = np.array(sim.particle_energies)
        assert per_particle == pytest.approx([e01 / 2, e01 / 2, 0.0], rel=1e-12, abs=1e-15)
        forces = np.array(sim.forces)
        assert np.abs(forces[2]).max() == 0.0
        # The bond holds as long as its energy stays below the threshold ...
        sim.positions = positions
        assert sim.energy() == pytest.approx(e01, rel=1e-12)
        # ... and breaks one configuration after it stops acting: 1 pulled away, the bond (0, 1) at zero
        # energy keeps 0 from 2 once more, then 0 and 2 are free again.
        apart = positions.copy()
        apart[1] = [2.5, 1.0, 0.0]
        sim.positions = apart
        assert sim.energy() == 0.0
        sim.positions = apart
        e02_apart = pair_energy(apart, directions, patches, 0, 2)
        assert sim.energy() == pytest.approx(e02_apart, rel=1e-12)


# ---- input errors ---------------------------------------------------------------------------------

def expect_input_error(options, entry, fragment):
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.StructmdError) as error:
            sim.load(document(POSITIONS, random_quaternions(3, 1), entry))
    assert fragment in str(error.value)


def test_bad_inputs_name_their_path(options):
    entry, _ = cosine_case()
    entry["patchesTopology"]["structure"]["data"][2][2] = 7
    expect_input_error(options, entry, "patchesTopology.structure.data[2][2]: particle id 7 does not exist")
    entry, _ = cosine_case()
    entry["patchesTopology"]["forceField"]["cosine"]["data"][0][4] = -1.0
    expect_input_error(options, entry, "cosine.data[0][4]: expected a positive number")
    entry, _ = cosrap_case()
    entry["patchesTopology"]["forceField"]["cosrap"]["data"][1][6] = list(R_SE)
    expect_input_error(options, entry, "expected the transpose of the rotation R")
    entry, _ = cosine_case()
    entry["patchesTopology"]["structure"]["data"][0][1] = "X"
    expect_input_error(options, entry, "unknown patch type 'X'")


# ---- writing --------------------------------------------------------------------------------------

def read_sp(path):
    frames, rows = [], None
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                rows = []
                frames.append(rows)
            elif line.strip():
                rows.append([float(v) for v in line.split()])
    return [np.array(r) for r in frames]


def test_write_patchy_particles_reads_back(options, tmp_path):
    entry, _ = combined_case()
    directions = random_quaternions(3, 9)
    out = os.path.join(str(tmp_path), "patchy")
    steps = {"write": {"type": ["WriteStep", "WritePatchyParticlesStep"],
                       "parameters": {"intervalStep": 1, "outputFilePath": out, "outputFormat": "sp"}}}
    doc = document(POSITIONS, directions, entry, steps)
    # The rigid-body Brownian integrator turns the particles by the patches' torques.
    doc["integrator"] = {"bd": {"type": ["Brownian", "EulerMaruyamaRigidBody"],
                                "parameters": {"timeStep": 0.001, "viscosity": 1.0}},
                         "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
                                      "data": [[1, "bd", 3]]}}
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        sim.step(3)
        positions = np.array(sim.positions)
        final_directions = np.array(sim.orientations)
    frames = read_sp(out + ".sp")
    assert len(frames) == 4
    assert np.abs(final_directions - directions).max() > 1e-4
    for frame, (x, q) in ((frames[0], (POSITIONS, directions)), (frames[-1], (positions, final_directions))):
        assert frame.shape == (3 + len(PATCHES), 5)
        sites, _ = patch_sites(x, q, PATCHES)
        assert frame[:3, :3] == pytest.approx(x, abs=1e-6)
        assert frame[3:, :3] == pytest.approx(sites, abs=1e-6)
        # Types: the particles' (A = 0), a gap, then the patches' S = 2, E = 3; radii of the patch types.
        assert list(frame[:, 4]) == [0, 0, 0] + [2 if t == "S" else 3 for _, t, _ in PATCHES]
        assert list(frame[3:, 3]) == [0.1 if t == "S" else 0.2 for _, t, _ in PATCHES]


def test_the_patches_state_integrator_moves_as_the_rigid_body_one(options):
    """["Brownian","EulerMaruyamaRigidBodyPatchesState"] is EulerMaruyamaRigidBody with the patches'
    state transitions, which the dynamic patch term makes by its own rule: the same input under either
    name gives the same trajectory, bit for bit, through dynamic bonds and turning bodies."""
    positions, directions, _, entry = bonding_system(dynamic=True)
    trajectories = []
    for name in ("EulerMaruyamaRigidBody", "EulerMaruyamaRigidBodyPatchesState"):
        doc = document(positions, directions, entry)
        doc["integrator"] = {"bd": {"type": ["Brownian", name], "parameters": {"timeStep": 0.001, "viscosity": 1.0}},
                             "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
                                          "data": [[1, "bd", 50]]}}
        with structmd.Simulation(options) as sim:
            sim.load(doc)
            sim.step(50)
            trajectories.append((np.array(sim.positions), np.array(sim.orientations)))
    (x, q), (x_alias, q_alias) = trajectories
    assert np.abs(q - directions).max() > 1e-3, "the bodies did not turn"
    np.testing.assert_array_equal(x_alias, x)
    np.testing.assert_array_equal(q_alias, q)


def test_potential_measure_writes_the_patches_torques(options, tmp_path):
    entry, _ = cosrap_case()
    directions = random_quaternions(3, 4)
    path = str(tmp_path / "pot.dat")
    steps = {"pot": {"type": ["ParticlesListMeasure", "PotentialMeasure"],
                     "parameters": {"intervalStep": 1, "outputFilePath": path},
                     "labels": ["id"], "data": [[0], [1], [2]]}}
    doc = document(POSITIONS, directions, entry, steps)
    doc["integrator"] = {"still": {"type": ["None", "None"]},
                         "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
                                      "data": [[1, "still", 1]]}}
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        sim.step(1)
        forces = np.array(sim.forces)
        torques = np.array(sim.torques)
        energies = np.array(sim.particle_energies)
    rows = [line.split() for line in open(path) if not line.startswith("#")][:3]
    values = np.array([[float(v) for v in row[1:]] for row in rows])
    assert np.abs(torques).max() > 0.1
    assert values[:, 0] == pytest.approx(energies, rel=1e-12)
    assert values[:, 1:4] == pytest.approx(forces, rel=1e-12)
    assert values[:, 5:8] == pytest.approx(torques, rel=1e-12)
