"""["TopologicalMeasures","PatchPolymers"]: polymers of dynamically bonded patchy monomers (one start patch S
and one end patch E each) and a surface (a linker patch L under ["SurfacePatches","Linker"]).

The scenario places the monomers so that every bond is known by construction (an S patch coincides with
one E patch, or every other patch is beyond the cutoff), in phases moved from Python between firings: free
monomers, chains, a merged chain longer than maxLen, a ring, the ring opened, everything apart again, with
monomers reaching and leaving the surface. The expected files are counted here from the positions alone:
bonds from coincident patches, polymers by walking the bond graph, the surface from the linker energy,
and the transition counts by replaying the documented events (bonds broken, then bonds made, then
surface changes, each in id order) over that graph. A thermal run checks the step's bookkeeping against
the same graph replay of its own Events.dat."""

import math
import os

import numpy as np
import pytest

import structmd

BOX = 40.0
RC = 0.3          # the S-E cosine's range; coincident patches bond, others are > 1 apart
SURFACE = -10.0   # the linker's plane
LINKER = {"epsilon": 2.0, "sigma": 0.05}
LINKER_OFFSET = [0.0, 0.0, -0.4]
THRESHOLD = -1.0
MAX_LEN = 3
INTERVAL = 4
N = 8

EVENT_DTYPE = np.dtype([("step", "<u8"), ("id", "<i4"), ("type", "<i4"), ("info", "<i4")])
PP, DP, S_EVENT, B_EVENT = 0, 2, 4, 5


def z_quaternion(angle):
    return [math.cos(angle / 2), 0.0, 0.0, math.sin(angle / 2)]


def rotation_z(q):
    angle = 2 * math.atan2(q[3], q[0])
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def document(positions, directions, steps, temperature=0.0, surface=True):
    """Monomer i: particle i with patches S (+0.5 x) and E (-0.5 x) in the bonded entry, and L below it
    in the surface entry."""
    bonded = {
        "type": ["PatchyParticles", "DynamicallyBondedPatchyParticles"],
        "patchesState": {"labels": ["id", "position"],
                         "data": [[2 * i + k, [0.5 if k == 0 else -0.5, 0.0, 0.0]] for i in range(N) for k in (0, 1)]},
        "patchesGlobal": {
            "fundamental": {"type": ["Fundamental", "DynamicallyBondedPatchyParticles"],
                            "parameters": {"energyThreshold": 0.0}},
            "types": {"type": ["Types", "Basic"], "labels": ["name", "radius"], "data": [["S", 0.1], ["E", 0.1]]}},
        "patchesTopology": {
            "structure": {"labels": ["id", "type", "parentId"],
                          "data": [[2 * i + k, "S" if k == 0 else "E", i] for i in range(N) for k in (0, 1)]},
            "forceField": {
                "patchList": {"type": ["VerletConditionalListSet", "interDifferentType"],
                              "parameters": {"cutOffVerletFactor": 1.2}},
                "cosine": {"type": ["NonBondedPatches", "DistanceSwitchCosine"], "parameters": {"condition": "inter"},
                           "labels": ["name_i", "name_j", "E", "K", "rc"], "data": [["S", "E", 10.0, 1.0, RC]]}}}}
    force_field = {"bonding": bonded}
    if surface:
        force_field["surface"] = {
            "type": ["PatchyParticles", "PatchyParticles"],
            "patchesState": {"labels": ["id", "position"], "data": [[i, LINKER_OFFSET] for i in range(N)]},
            "patchesGlobal": {"types": {"type": ["Types", "Basic"], "labels": ["name", "radius"], "data": [["L", 0.1]]}},
            "patchesTopology": {
                "structure": {"labels": ["id", "type", "parentId"], "data": [[i, "L", i] for i in range(N)]},
                "forceField": {"linker": {"type": ["SurfacePatches", "Linker"], "parameters": {"surfacePosition": SURFACE},
                                          "labels": ["name", "epsilon", "sigma"],
                                          "data": [["L", LINKER["epsilon"], LINKER["sigma"]]]}}}}
    return {
        "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": "polymers", "seed": 5}}},
        "global": {
            "types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"], "data": [["A", 1.0, 0.5, 0.0]]},
            "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"], "data": [[[BOX] * 3, temperature]]}},
        "integrator": {
            "bd": {"type": ["Brownian", "EulerMaruyamaRigidBody"], "parameters": {"timeStep": 0.001, "viscosity": 1.0}},
            "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
                         "data": [[1, "bd", 100000]]}},
        "state": {"labels": ["id", "position", "direction"],
                  "data": [[i, list(map(float, x)), list(map(float, q))] for i, (x, q) in enumerate(zip(positions, directions))]},
        "topology": {"structure": {"labels": ["id", "type"], "data": [[i, "A"] for i in range(N)]},
                     "forceField": force_field},
        "simulationStep": steps,
    }


def polymers_step(prefix, interval=INTERVAL, **extra):
    parameters = {"intervalStep": interval, "outputFilePath": prefix, "maxLen": MAX_LEN,
                  "surfaceEnergyThreshold": THRESHOLD, "bufferSize": 10, "writeEvents": True}
    parameters.update(extra)
    return {"poly": {"type": ["TopologicalMeasures", "PatchPolymers"], "parameters": parameters}}


# ---- the scenario's geometry ----------------------------------------------------------------------

def place_chain(positions, directions, ids, origin):
    """ids[j]'s S patch on ids[j + 1]'s E patch: a straight chain along x."""
    for j, i in enumerate(ids):
        positions[i] = np.asarray(origin, float) + [j, 0.0, 0.0]
        directions[i] = z_quaternion(0.0)


def place_ring(positions, directions, ids, origin):
    """Monomer j on the edge (v_j, v_j+1) of a unit polygon, along it: its E patch on v_j, S on v_j+1."""
    k = len(ids)
    radius = 0.5 / math.sin(math.pi / k)
    vertices = [np.asarray(origin, float) + radius * np.array([math.cos(2 * math.pi * j / k), math.sin(2 * math.pi * j / k), 0.0])
                for j in range(k)]
    for j, i in enumerate(ids):
        a, b = vertices[j], vertices[(j + 1) % k]
        positions[i] = (a + b) / 2
        directions[i] = z_quaternion(math.atan2(b[1] - a[1], b[0] - a[0]))


def scattered():
    positions = np.array([[-15.0 + 4.0 * i, 12.0, 0.0] for i in range(N)])
    directions = np.array([z_quaternion(0.0)] * N)
    return positions, directions


def on_surface_height(positions, ids):
    for i in ids:
        positions[i][2] = SURFACE - LINKER_OFFSET[2]


def phases():
    """The configurations the test moves the monomers through, one per firing after the first."""
    out = []
    p, d = scattered()
    on_surface_height(p, [6, 7])
    out.append((p.copy(), d.copy()))                                  # free; 6 and 7 on the surface
    place_chain(p, d, [0, 1, 2], [-10.0, 0.0, 0.0])
    place_chain(p, d, [3, 4], [0.0, 0.0, 0.0])
    out.append((p.copy(), d.copy()))                                  # chains 0-1-2 and 3-4
    place_chain(p, d, [5, 0, 1, 2, 3, 4], [-10.0, 0.0, 0.0])
    p[4][2] = p[5][2] = p[0][2] = p[1][2] = p[2][2] = p[3][2] = SURFACE - LINKER_OFFSET[2]
    out.append((p.copy(), d.copy()))                                  # one chain of 6 on the surface
    place_ring(p, d, [0, 1, 2, 3], [5.0, -5.0, 0.0])
    p[4] = [10.0, 5.0, SURFACE - LINKER_OFFSET[2]]
    p[5] = [-10.0, 5.0, 0.0]
    out.append((p.copy(), d.copy()))                                  # a ring of 4; 4 alone on the surface
    place_chain(p, d, [2, 3, 0, 1], [-5.0, -5.0, 0.0])
    place_chain(p, d, [6, 7], [5.0, 10.0, SURFACE - LINKER_OFFSET[2]])
    out.append((p.copy(), d.copy()))                                  # the ring opened between 1 and 2; 6-7
    p, d = scattered()
    on_surface_height(p, [7])
    out.append((p.copy(), d.copy()))                                  # all apart; 7 alone on the surface
    return out


# ---- the reference, from the positions ---------------------------------------------------------------

def sites(positions, directions, offset):
    return np.array([np.asarray(x) + rotation_z(q) @ np.asarray(offset) for x, q in zip(positions, directions)])


def geometric_bonds(positions, directions):
    """By monomer, the monomer whose E patch its S patch sits on (None when its S patch is free)."""
    s = sites(positions, directions, [0.5, 0.0, 0.0])
    e = sites(positions, directions, [-0.5, 0.0, 0.0])
    bonds = {}
    for i in range(N):
        near = [j for j in range(N) if j != i and np.linalg.norm(s[i] - e[j]) < 1e-9]
        far = [j for j in range(N) if j != i and 1e-9 <= np.linalg.norm(s[i] - e[j]) < 2 * RC]
        assert len(near) <= 1 and not far, "the scenario's patches must coincide or stay apart"
        bonds[i] = near[0] if near else None
    return bonds


def geometric_surface(positions, directions):
    z = sites(positions, directions, LINKER_OFFSET)[:, 2]
    energy = -LINKER["epsilon"] * np.exp(-(z - SURFACE) ** 2 / (2 * LINKER["sigma"]))
    return [bool(u < THRESHOLD) for u in energy]


class Graph:
    """Monomers joined by start-patch bonds: polymers are its components, walked from the bonds."""

    def __init__(self):
        self.next = {}      # i -> the monomer i's S patch is bonded to
        self.surface = [False] * N

    def previous(self, i):
        return next((j for j, k in self.next.items() if k == i), None)

    def polymer(self, i):
        """(monomers in order, is a ring, position of i): back to the first monomer (or round the ring
        to the one after i), then forward."""
        start, ring = i, False
        while True:
            before = self.previous(start)
            if before is None:
                break
            if before == i:
                ring = True
                break
            start = before
        chain = [start]
        while self.next.get(chain[-1]) is not None and self.next[chain[-1]] != start:
            chain.append(self.next[chain[-1]])
        return chain, ring, chain.index(i)

    def key(self, i):
        chain, ring, index = self.polymer(i)
        surface = any(self.surface[m] for m in chain)
        head = "S_" if surface else "B_"
        before, after = index, len(chain) - 1 - index
        if before + after > MAX_LEN:
            return head + ("RM" if ring else "LM")
        return head + (f"R_{before + after}" if ring else f"L_{before}_{after}")

    def polymers(self):
        seen, out = set(), []
        for i in range(N):
            if i not in seen:
                chain, ring, _ = self.polymer(i)
                seen.update(chain)
                out.append(chain)
        return out

    def distributions(self):
        polymers = self.polymers()
        size = max(len(c) for c in polymers)
        bulk, surface = [0] * size, [0] * size
        for chain in polymers:
            (surface if any(self.surface[m] for m in chain) else bulk)[len(chain) - 1] += 1
        return bulk, surface


class Replay:
    """The documented bookkeeping: each event moves its monomer to its new state; (s, s) gathers the
    steps spent in s, (s, t) counts the transitions."""

    def __init__(self, step):
        self.graph = Graph()
        self.recorded = {i: (step, self.graph.key(i)) for i in range(N)}
        self.transitions = {}
        self.events = []

    def record(self, step, i):
        old_step, old = self.recorded[i]
        now = self.graph.key(i)
        self.transitions[(old, old)] = self.transitions.get((old, old), 0) + step - old_step
        self.transitions[(old, now)] = self.transitions.get((old, now), 0) + 1
        self.recorded[i] = (step, now)

    def apply(self, step, kind, i, info):
        self.events.append((step, i, kind, info))
        if kind == DP:
            assert self.graph.next.pop(i) == info
        elif kind == PP:
            assert i not in self.graph.next
            self.graph.next[i] = info
        else:
            self.graph.surface[i] = kind == S_EVENT
        self.record(step, i)

    def fire(self, step, bonds, surface):
        """The events between the last state and (bonds, surface), in the documented order."""
        for i in range(N):
            if self.graph.next.get(i) is not None and bonds.get(i) != self.graph.next[i]:
                self.apply(step, DP, i, self.graph.next[i])
        for i in range(N):
            if bonds.get(i) is not None and bonds[i] != self.graph.next.get(i):
                self.apply(step, PP, i, bonds[i])
        for i in range(N):
            if surface[i] != self.graph.surface[i]:
                self.apply(step, S_EVENT if surface[i] else B_EVENT, i, 0)


# ---- reading the files ----------------------------------------------------------------------------

def read_blocks(path):
    """{step: [rows]} of a file of '# step' blocks."""
    blocks, rows = {}, None
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                rows = blocks.setdefault(int(line[1:]), [])
            elif line.strip():
                rows.append(line.split())
    return blocks


def distribution_of(rows):
    assert [int(r[0]) for r in rows] == list(range(len(rows)))
    return [int(r[1]) for r in rows]


def transitions_of(rows):
    return {(r[0], r[1]): int(r[2]) for r in rows}


def check_outputs(prefix, expected):
    """expected: {step: (bulk, surface, fraction, transitions)}."""
    bulk = read_blocks(prefix + "PolymerDistribution.dat")
    surface = read_blocks(prefix + "SurfacePolymerDistribution.dat")
    transitions = read_blocks(prefix + "TransitionMatrix.dat")
    fractions = dict((int(a), float(b)) for a, b in (line.split() for line in open(prefix + "FractionMonomersInSurface.dat")))
    assert sorted(bulk) == sorted(expected) == sorted(surface) == sorted(transitions) == sorted(fractions)
    for step, (b, s, fraction, t) in expected.items():
        assert distribution_of(bulk[step]) == b, step
        assert distribution_of(surface[step]) == s, step
        assert fractions[step] == pytest.approx(fraction, rel=1e-15), step
        assert transitions_of(transitions[step]) == t, step


def snapshot(replay):
    bulk, surface = replay.graph.distributions()
    return bulk, surface, sum(replay.graph.surface) / N, dict(replay.transitions)


# ---- tests ------------------------------------------------------------------------------------------

def test_polymers_rings_and_surface_match_the_positions(options, tmp_path):
    prefix = str(tmp_path / "pp_")
    configurations = phases()
    positions, directions = scattered()
    with structmd.Simulation(options) as sim:
        sim.load(document(positions, directions, polymers_step(prefix)))
        sim.step(INTERVAL)  # fires at steps 0 and INTERVAL: every monomer free and in the bulk
        replay = Replay(0)
        expected = {}
        for step in (0, INTERVAL):
            replay.fire(step, geometric_bonds(positions, directions), geometric_surface(positions, directions))
            expected[step] = snapshot(replay)
        seen_states = set()
        for p, d in configurations:
            # A move, then a firing INTERVAL steps later: the bonds settle within three configurations
            # (a bond breaks one configuration after it stops acting, a patch freed then bonds anew).
            sim.positions = p
            sim.orientations = d
            sim.step(INTERVAL)
            step = sim.step_number
            now_positions, now_directions = np.array(sim.positions), np.array(sim.orientations)
            assert now_positions == pytest.approx(p, abs=1e-9)  # nothing pulls: every patch pair is at rest
            replay.fire(step, geometric_bonds(p, d), geometric_surface(p, d))
            expected[step] = snapshot(replay)
            seen_states.update(replay.graph.key(i) for i in range(N))
    check_outputs(prefix, expected)
    # The scenario went through every kind of state.
    assert {"B_L_0_0", "S_L_0_0", "B_L_1_1", "S_LM", "B_R_3", "S_L_0_1", "B_L_2_1"} <= seen_states
    events = np.fromfile(prefix + "Events.dat", dtype=EVENT_DTYPE)
    assert [tuple(int(v) for v in e) for e in events] == replay.events
    assert {PP, DP, S_EVENT, B_EVENT} == {int(e["type"]) for e in events}


def test_thermal_run_agrees_with_its_events(options, tmp_path):
    """Monomers in reach of one another under thermal motion: bonds form and break at random. Replaying
    Events.dat over the bond graph gives every file the step wrote."""
    prefix = str(tmp_path / "hot_")
    positions = np.array([[1.02 * i - 4.0, 0.03 * (i % 3), SURFACE - LINKER_OFFSET[2] + 0.1 * (i % 2)] for i in range(N)])
    directions = np.array([z_quaternion(0.0)] * N)
    doc = document(positions, directions, polymers_step(prefix, interval=1), temperature=1.5)
    doc["topology"]["forceField"]["bonding"]["patchesTopology"]["forceField"]["cosine"]["data"][0][2] = 3.0
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        sim.step(600)
    events = np.fromfile(prefix + "Events.dat", dtype=EVENT_DTYPE)
    assert len(events) > 20 and {PP, DP} <= {int(e["type"]) for e in events}
    replay = Replay(0)
    expected = {}
    by_step = {}
    for e in events:
        by_step.setdefault(int(e["step"]), []).append(e)
    bulk = read_blocks(prefix + "PolymerDistribution.dat")
    for step in sorted(bulk):
        for e in by_step.get(step, []):
            replay.apply(step, int(e["type"]), int(e["id"]), int(e["info"]))
        expected[step] = snapshot(replay)
    assert sorted(bulk) == list(range(601))
    check_outputs(prefix, expected)


def expect_input_error(options, doc, fragment):
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.StructmdError) as error:
            sim.load(doc)
    assert fragment in str(error.value)


def test_bad_parameters_name_their_path(options, tmp_path):
    prefix = str(tmp_path / "bad_")
    positions, directions = scattered()

    def with_step(**extra):
        return document(positions, directions, polymers_step(prefix, **extra))

    doc = with_step()
    del doc["simulationStep"]["poly"]["parameters"]["bufferSize"]
    expect_input_error(options, doc, "simulationStep.poly.parameters.bufferSize: missing required parameter")
    expect_input_error(options, with_step(startType="X"),
                       "simulationStep.poly.parameters.startType: no patch type 'X' in forceField entry 'bonding'")
    expect_input_error(options, with_step(linkerType="S"),
                       "simulationStep.poly.parameters.linkerType: no patch type 'S' in forceField entry 'surface'")
    expect_input_error(options, with_step(endType="S"), "simulationStep.poly.parameters.endType")
    expect_input_error(options, with_step(maxLen=-1), "simulationStep.poly.parameters.maxLen")
    expect_input_error(options, with_step(bufferSize=0), "simulationStep.poly.parameters.bufferSize")
    expect_input_error(options, with_step(surfaceEnergyThreshold="low"),
                       "simulationStep.poly.parameters.surfaceEnergyThreshold")
    expect_input_error(options, document(positions, directions, polymers_step(str(tmp_path / "missing" / "pp_"))),
                       "simulationStep.poly.parameters.outputFilePath")
    doc = with_step()
    del doc["topology"]["forceField"]["bonding"]
    expect_input_error(options, doc, "simulationStep.poly: PatchPolymers needs a "
                                     "[\"PatchyParticles\",\"DynamicallyBondedPatchyParticles\"] forceField entry")
    doc = with_step()
    doc["topology"]["forceField"]["bonding"]["patchesTopology"]["forceField"]["cosine"]["data"].append(
        ["E", "E", 10.0, 1.0, RC])
    expect_input_error(options, doc, "simulationStep.poly: forceField entry 'bonding' lets patches of type 'E' bond "
                                     "to each other")
    doc = with_step()
    doc["topology"]["forceField"]["bonding"]["patchesTopology"]["structure"]["data"][3][1] = "S"
    expect_input_error(options, doc, "simulationStep.poly: particle 1 has more than one patch of type 'S'")


def test_without_a_surface_only_the_bulk_files_are_written(options, tmp_path):
    prefix = str(tmp_path / "bulk_")
    positions, directions = scattered()
    place_chain(positions, directions, [1, 2, 3], [0.0, 0.0, 0.0])
    with structmd.Simulation(options) as sim:
        sim.load(document(positions, directions, polymers_step(prefix, writeEvents=False), surface=False))
        sim.step(2 * INTERVAL)
    written = sorted(f for f in os.listdir(tmp_path) if f.startswith("bulk_"))
    assert written == ["bulk_PolymerDistribution.dat", "bulk_TransitionMatrix.dat"]
    blocks = read_blocks(prefix + "PolymerDistribution.dat")
    # The chain 1-2-3 bonds from the second configuration on: at step 4 one polymer of 3 and 5 monomers.
    assert distribution_of(blocks[0]) == [N]
    assert distribution_of(blocks[INTERVAL]) == [N - 3, 0, 1]
