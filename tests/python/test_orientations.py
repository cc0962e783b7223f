"""Orientations: the state's "direction" quaternions kept by the engine, ["External","ConstantTorque"],
the rigid-body Brownian integrator ["Brownian","EulerMaruyamaRigidBody"] (rotational diffusion and
deterministic rotation against formulas written here), the API's orientations and torques, their
checkpoint, and the WriteStep formats with orientations (spo, svv, itpd) read back by readers written
from UAMMD-structured's description of each format."""

import math

import numpy as np
import pytest

import structmd

KT = 1.0  # units None: k_B = 1
TYPES = [["small", 1.0, 0.5, 0.0], ["large", 1.0, 1.0, 0.0]]  # name, mass, radius, charge
RADIUS = {row[0]: row[2] for row in TYPES}
BOX = 40.0


def document(positions, types, integrators=None, schedule=(), force_field=None, directions=None,
             temperature=KT, seed=7, steps_section=None, groups=None):
    """integrators: {name: entry}; schedule: [(name, steps), ...]; directions: [[q0, q1, q2, q3], ...]."""
    labels = ["id", "position"] + (["direction"] if directions is not None else [])
    rows = []
    for i, position in enumerate(positions):
        row = [i, [float(c) for c in position]]
        if directions is not None:
            row.append([float(c) for c in directions[i]])
        rows.append(row)
    doc = {
        "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": "orientations", "seed": seed}}},
        "global": {
            "types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"], "data": TYPES},
            "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"],
                         "data": [[[BOX, BOX, BOX], temperature]]},
        },
        "state": {"labels": labels, "data": rows},
        "topology": {"structure": {"labels": ["id", "type"], "data": [[i, t] for i, t in enumerate(types)]},
                     "forceField": dict(force_field or {})},
    }
    if groups:
        doc["topology"]["forceField"]["groups"] = {"type": ["Groups", "GroupsList"],
                                                   "labels": ["name", "type", "selection"], "data": groups}
    if integrators:
        doc["integrator"] = dict(integrators, schedule={
            "type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
            "data": [[k + 1, name, steps] for k, (name, steps) in enumerate(schedule)]})
    if steps_section:
        doc["simulationStep"] = steps_section
    return doc


def rigid_body(time_step, viscosity=None, **extra):
    parameters = {"timeStep": time_step, **extra}
    if viscosity is not None:
        parameters["viscosity"] = viscosity
    return {"type": ["Brownian", "EulerMaruyamaRigidBody"], "parameters": parameters}


def torque_entry(torque, **extra):
    return {"type": ["External", "ConstantTorque"], "parameters": {"constantTorque": list(torque), **extra}}


def random_quaternions(n, seed):
    q = np.random.default_rng(seed).normal(size=(n, 4))
    return q / np.linalg.norm(q, axis=1)[:, None]


def rotation_matrix(q):
    """R(q) of UAMMD-structured's State documentation, q = [q0, q1, q2, q3] scalar first."""
    q0, q1, q2, q3 = q
    return np.array([[1 - 2 * q2 * q2 - 2 * q3 * q3, 2 * q1 * q2 - 2 * q0 * q3, 2 * q1 * q3 + 2 * q0 * q2],
                     [2 * q1 * q2 + 2 * q0 * q3, 1 - 2 * q1 * q1 - 2 * q3 * q3, 2 * q2 * q3 - 2 * q0 * q1],
                     [2 * q1 * q3 - 2 * q0 * q2, 2 * q2 * q3 + 2 * q0 * q1, 1 - 2 * q1 * q1 - 2 * q2 * q2]])


def axis_rotation(axis, angle):
    """The rotation matrix of angle about the unit axis (Rodrigues)."""
    k = np.array(axis, dtype=float) / np.linalg.norm(axis)
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + math.sin(angle) * K + (1 - math.cos(angle)) * K @ K


def grid(n, spacing=1.0):
    side = int(math.ceil(n ** (1 / 3)))
    points = [[(i - side / 2) * spacing, (j - side / 2) * spacing, (k - side / 2) * spacing]
              for i in range(side) for j in range(side) for k in range(side)]
    return points[:n]


def tolerance(options):
    return 1e-5 if options.get("precision") == "single" else 1e-12


# ---- the state's directions and the API ---------------------------------------------------------

def test_directions_are_kept_normalised_and_the_default_is_the_identity(options):
    q = random_quaternions(4, seed=1)
    printed = np.round(q, 5)  # a generator's few digits: within the reader's 1e-4 of unit norm
    with structmd.Simulation(options) as sim:
        sim.load(document(grid(4), ["small"] * 4, directions=printed))
        expected = printed / np.linalg.norm(printed, axis=1)[:, None]
        np.testing.assert_allclose(sim.orientations, expected, atol=tolerance(options))
    with structmd.Simulation(options) as sim:
        sim.load(document(grid(3), ["small"] * 3))
        np.testing.assert_array_equal(sim.orientations, [[1.0, 0.0, 0.0, 0.0]] * 3)


def test_set_orientations_round_trips_and_refuses_a_non_unit_quaternion(options):
    n = 5
    with structmd.Simulation(options) as sim:
        sim.load(document(grid(n), ["small"] * n))
        q = random_quaternions(n, seed=2)
        sim.orientations = q
        np.testing.assert_allclose(sim.orientations, q, atol=tolerance(options))
        bad = q.copy()
        bad[3] *= 1.01
        with pytest.raises(structmd.ArgumentError, match=r"particle id 3 is not a unit quaternion"):
            sim.orientations = bad
        bad = q.copy()
        bad[2, 1] = float("nan")
        with pytest.raises(structmd.ArgumentError, match=r"q\[9\]: not a finite number \(particle id 2\)"):
            sim.orientations = bad
        with pytest.raises(structmd.ArgumentError, match=r"expected shape \(5, 4\)"):
            sim.orientations = q[:, :3]
        np.testing.assert_allclose(sim.orientations, q, atol=tolerance(options))  # unchanged by the refusals


# ---- ConstantTorque -----------------------------------------------------------------------------

def test_constant_torques_add_up_on_their_groups_and_exert_no_force(options):
    n = 6
    t1, t2 = [0.5, -1.25, 2.0], [-0.125, 0.75, 0.25]
    force_field = {"spin": torque_entry(t1), "twist": torque_entry(t2, group="firstThree")}
    with structmd.Simulation(options) as sim:
        sim.load(document(grid(n, 2.0), ["small"] * n, force_field=force_field,
                          groups=[["firstThree", "Ids", [0, 1, 2]]]))
        expected = np.array([np.add(t1, t2)] * 3 + [t1] * 3)
        np.testing.assert_array_equal(sim.torques, expected)  # sums of numbers exact in binary
        np.testing.assert_array_equal(sim.forces, 0.0)
        assert sim.energy("potential") == 0.0
        assert sim.energy("spin") == 0.0


def test_a_simulation_without_torque_terms_reads_zero_torques(options):
    with structmd.Simulation(options) as sim:
        sim.load(document(grid(3), ["small"] * 3))
        np.testing.assert_array_equal(sim.torques, 0.0)


# ---- EulerMaruyamaRigidBody ---------------------------------------------------------------------

def test_rotational_diffusion_decorrelates_a_body_axis_as_exp_minus_2_dr_t(options):
    """Free spheres: <u(t) . u(0)> = exp(-2 D_r t) for each body axis, D_r = k_B T / (8 pi eta a^3),
    within four standard errors of the mean over the particles and axes."""
    n, dt, steps, every = 3000, 0.01, 120, 40
    radius = RADIUS["large"]
    d_r = 0.5
    viscosity = KT / (8.0 * math.pi * d_r * radius ** 3)
    q0 = random_quaternions(n, seed=3)
    axes0 = np.array([rotation_matrix(q) for q in q0])
    with structmd.Simulation(options) as sim:
        sim.load(document(grid(n, 0.5), ["large"] * n, {"rigid": rigid_body(dt, viscosity)}, [("rigid", steps)],
                          directions=q0))
        for done in range(every, steps + 1, every):
            sim.step(every)
            q = sim.orientations
            np.testing.assert_allclose(np.linalg.norm(q, axis=1), 1.0, atol=1e-12)
            axes = np.array([rotation_matrix(row) for row in q])
            correlation = np.einsum("nij,nij->nj", axes, axes0)  # u_j(t) . u_j(0) for each body axis j
            mean = correlation.mean()
            error = correlation.mean(axis=1).std() / math.sqrt(n)
            expected = math.exp(-2.0 * d_r * done * dt)
            assert abs(mean - expected) < 4.0 * error, (done, mean, expected, error)


def test_a_constant_torque_at_zero_temperature_turns_each_particle_by_mr_torque_t(options):
    """Rotation angle M_r |T| t about the torque's axis, M_r = 1 / (8 pi eta a^3), from any starting
    orientation; the body axes turn as R(axis, angle) R(q0)."""
    n, dt, steps = 4, 0.002, 250
    viscosity = 0.3
    torque = np.array([3.0, -2.0, 6.0])
    types = ["small", "large", "small", "large"]
    q0 = random_quaternions(n, seed=4)
    with structmd.Simulation(options) as sim:
        sim.load(document(grid(n, 3.0), types, {"rigid": rigid_body(dt, viscosity)}, [("rigid", steps)],
                          force_field={"spin": torque_entry(torque)}, directions=q0, temperature=0.0))
        start = sim.positions
        sim.run()
        q = sim.orientations
        np.testing.assert_array_equal(sim.positions, start)  # no force, no noise: no translation
    angles = []
    for i, type_name in enumerate(types):
        mobility = 1.0 / (8.0 * math.pi * viscosity * RADIUS[type_name] ** 3)
        angles.append(mobility * np.linalg.norm(torque) * steps * dt)
        expected = axis_rotation(torque, angles[-1]) @ rotation_matrix(q0[i])
        np.testing.assert_allclose(rotation_matrix(q[i]), expected, atol=1e-10)
    assert min(angles) > 0.4 and max(angles) > 3.0  # turns large enough that a wrong axis or mobility shows


def test_without_a_viscosity_the_mobilities_come_from_the_state_columns(options):
    """D = k_B T / (6 pi eta a) and D_r = k_B T / (8 pi eta a^3) in the state give the trajectory
    (positions and orientations) that viscosity eta gives, with the same seed."""
    n, dt, steps, viscosity = 8, 0.005, 30, 0.4
    types = ["small", "large"] * (n // 2)
    radius = np.array([RADIUS[t] for t in types])
    results = []
    for columns in (False, True):
        doc = document(grid(n, 3.0), types, {"rigid": rigid_body(dt, None if columns else viscosity)},
                       [("rigid", steps)], force_field={"spin": torque_entry([0.0, 0.0, 1.0])})
        if columns:
            doc["state"]["labels"] += ["translationalSelfDiffusion", "rotationalSelfDiffusion"]
            for row, a in zip(doc["state"]["data"], radius):
                row += [KT / (6.0 * math.pi * viscosity * a), KT / (8.0 * math.pi * viscosity * a ** 3)]
        with structmd.Simulation(options) as sim:
            sim.load(doc)
            sim.run()
            results.append((sim.positions, sim.orientations))
    np.testing.assert_allclose(results[1][0], results[0][0], atol=1e-10)
    np.testing.assert_allclose(results[1][1], results[0][1], atol=1e-10)
    assert np.any(np.abs(results[0][1] - [1.0, 0.0, 0.0, 0.0]) > 1e-2)


def test_a_missing_rotational_column_names_the_viscosity(options):
    doc = document(grid(2, 3.0), ["small"] * 2, {"rigid": rigid_body(0.01)}, [("rigid", 5)])
    doc["state"]["labels"].append("translationalSelfDiffusion")
    for row in doc["state"]["data"]:
        row.append(1.0)
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.InputError,
                           match=r"integrator\.rigid\.parameters\.viscosity: missing.*'rotationalSelfDiffusion'"):
            sim.load(doc)


def test_orientations_continue_from_a_checkpoint_as_without_it(options, tmp_path):
    n, dt = 10, 0.01
    doc = document(grid(n, 2.0), ["small", "large"] * (n // 2), {"rigid": rigid_body(dt, 0.5)}, [("rigid", 100)],
                   force_field={"spin": torque_entry([1.0, 0.5, 0.0])}, directions=random_quaternions(n, seed=5))
    path = str(tmp_path / "state.chk")
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        sim.step(20)
        sim.save_checkpoint(path)
        saved = sim.orientations
        sim.step(30)
        straight = sim.orientations
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        sim.load_checkpoint(path)
        np.testing.assert_array_equal(sim.orientations, saved)
        sim.step(30)
        np.testing.assert_array_equal(sim.orientations, straight)


def test_a_blow_up_puts_the_orientations_back_with_the_positions(options):
    """A step call that fails (here a force so large that the first move is infinite) returns to the
    state it started from, orientations included, though the rotation of that step came first."""
    n = 4
    force_field = {"spin": torque_entry([0.0, 0.0, 5.0]), "push": {"type": ["External", "ConstantForce"],
                                                                 "parameters": {"constantForce": [1e308, 0.0, 0.0]}}}
    doc = document(grid(n, 3.0), ["small"] * n, {"rigid": rigid_body(0.01, 1e-6)}, [("rigid", 10)],
                   force_field=force_field, directions=random_quaternions(n, seed=10))
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        before = sim.orientations
        with pytest.raises(structmd.NumericalError):
            sim.step(5)
        assert sim.step_number == 0
        np.testing.assert_array_equal(sim.orientations, before)


def test_a_checkpoint_without_orientations_restores_the_identity(options, tmp_path):
    doc = document(grid(3), ["small"] * 3)
    path = str(tmp_path / "plain.chk")
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        sim.save_checkpoint(path)
        sim.orientations = random_quaternions(3, seed=6)
        sim.load_checkpoint(path)
        np.testing.assert_array_equal(sim.orientations, [[1.0, 0.0, 0.0, 0.0]] * 3)


# ---- WriteStep formats with orientations --------------------------------------------------------

def write_run(options, tmp_path, output_format, steps=6, interval=3):
    """A rigid-body run writing every interval steps; returns the frames' (positions, radii, types,
    orientations) as the API gives them at those steps, and the file's text."""
    n = 5
    types = ["small", "large", "small", "large", "small"]
    base = str(tmp_path / "out")
    steps_section = {"write": {"type": ["WriteStep", "WriteStep"],
                               "parameters": {"intervalStep": interval, "outputFilePath": base,
                                              "outputFormat": output_format}}}
    doc = document(grid(n, 3.0), types, {"rigid": rigid_body(0.01, 0.5)}, [("rigid", steps)],
                   force_field={"spin": torque_entry([0.0, 2.0, 1.0])}, directions=random_quaternions(n, seed=8),
                   steps_section=steps_section)
    frames = []
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        radii = [RADIUS[t] for t in types]
        type_index = [0 if t == "small" else 1 for t in types]
        for k in range(steps // interval + 1):
            frames.append((sim.positions, np.array(radii), type_index, sim.orientations))
            if k < steps // interval:
                sim.step(interval)
    return frames, open(f"{base}.{output_format}").read()


def sp_frames(text):
    """superpunto: frames begin with '#Lx=..;Ly=..;Lz=..;'; each line is numbers."""
    frames = []
    for line in text.splitlines():
        if line.startswith("#"):
            frames.append([])
        else:
            frames[-1].append([float(v) for v in line.split()])
    return frames


def test_spo_marks_each_body_axis_with_a_small_sphere(options, tmp_path):
    frames, text = write_run(options, tmp_path, "spo")
    written = sp_frames(text)
    assert len(written) == len(frames)
    for (positions, radii, types, q), lines in zip(frames, written):
        assert len(lines) == 4 * len(positions)
        for i, (r, a, t) in enumerate(zip(positions, radii, types)):
            R = rotation_matrix(q[i])
            block = np.array(lines[4 * i:4 * i + 4])
            np.testing.assert_allclose(block[0], [*r, a, t], rtol=1e-7, atol=1e-7)
            for k in range(3):  # body x, y, z: at r + a R e_k, radius a/5, type (k + 2) t
                np.testing.assert_allclose(block[1 + k], [*(r + a * R[:, k]), 0.2 * a, (k + 2) * t],
                                           rtol=1e-7, atol=1e-7)


def test_svv_draws_each_body_axis_as_an_arrow(options, tmp_path):
    frames, text = write_run(options, tmp_path, "svv")
    written = sp_frames(text)
    assert len(written) == len(frames)
    for (positions, radii, types, q), lines in zip(frames, written):
        assert len(lines) == 4 * len(positions)
        for i, (r, a, t) in enumerate(zip(positions, radii, types)):
            R = rotation_matrix(q[i])
            block = lines[4 * i:4 * i + 4]
            np.testing.assert_allclose(block[0], [*r, a, t], rtol=1e-7, atol=1e-7)
            for k, color in enumerate((1, 5, 8)):
                np.testing.assert_allclose(block[1 + k], [*r, *(2 * a * R[:, k]), color], rtol=1e-7, atol=1e-7)


def test_itpd_lists_ids_types_positions_and_quaternions(options, tmp_path):
    frames, text = write_run(options, tmp_path, "itpd")
    lines = text.splitlines()
    cursor = 0
    for positions, _, types, q in frames:
        n = int(lines[cursor])
        assert n == len(positions) and lines[cursor + 1] == ""
        rows = np.array([[float(v) for v in line.split()] for line in lines[cursor + 2:cursor + 2 + n]])
        np.testing.assert_array_equal(rows[:, 0], np.arange(n))
        np.testing.assert_array_equal(rows[:, 1], types)
        np.testing.assert_allclose(rows[:, 2:5], positions, rtol=1e-7, atol=1e-7)
        np.testing.assert_allclose(rows[:, 5:9], q, rtol=1e-7, atol=1e-7)
        cursor += 2 + n
    assert cursor == len(lines)


# ---- MeanAngularCorrelation ---------------------------------------------------------------------

def test_mean_angular_correlation_follows_the_body_z_axes_of_its_group(options, tmp_path):
    """At zero temperature a torque along k turns each particle by phi_i = M_r,i |T| t about k, so
    e_z(t) . e_z(0) = cos phi + (1 - cos phi) (k . e_z(0))^2; the measure averages it over its group."""
    n, dt, steps, interval, viscosity = 6, 0.002, 300, 100, 0.3
    torque = np.array([1.0, 2.0, -2.0])
    k = torque / np.linalg.norm(torque)
    types = ["small", "large"] * (n // 2)
    q0 = random_quaternions(n, seed=9)
    path = tmp_path / "mac.dat"
    steps_section = {
        "groups": {"type": ["Groups", "GroupsList"], "labels": ["name", "type", "selection"],
                   "data": [["measured", "Ids", [0, 1, 3, 4]]]},
        "mac": {"type": ["GeometricalMeasure", "MeanAngularCorrelation"],
                "parameters": {"intervalStep": interval, "outputFilePath": str(path), "group": "measured"}}}
    with structmd.Simulation(options) as sim:
        sim.load(document(grid(n, 3.0), types, {"rigid": rigid_body(dt, viscosity)}, [("rigid", steps)],
                          force_field={"spin": torque_entry(torque)}, directions=q0, temperature=0.0,
                          steps_section=steps_section))
        sim.run()
    lines = path.read_text().splitlines()
    assert lines[0] == "#step time MAC"
    rows = np.array([[float(v) for v in line.split()] for line in lines[1:]])
    np.testing.assert_array_equal(rows[:, 0], np.arange(0, steps + 1, interval))
    members = [0, 1, 3, 4]
    for step, time, mac in rows:
        cosines = []
        for i in members:
            mobility = 1.0 / (8.0 * math.pi * viscosity * RADIUS[types[i]] ** 3)
            phi = mobility * np.linalg.norm(torque) * time
            along = k @ rotation_matrix(q0[i])[:, 2]
            cosines.append(math.cos(phi) + (1.0 - math.cos(phi)) * along ** 2)
        assert time == pytest.approx(step * dt, rel=1e-12)
        assert mac == pytest.approx(np.mean(cosines), abs=1e-9)
    assert rows[-1, 2] < 0.9  # the axes have turned enough for the check to mean something
