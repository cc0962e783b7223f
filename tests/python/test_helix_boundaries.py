"""["External","HelixBoundaries"]: a tube around a helix, tabulated on a grid and interpolated as
["External","ExternalTabulated"] is. The energy against the same interpolation written here in numpy
of the tube energy at the cell centres, with the distance to the helix found by dense sampling;
force = -grad U by central differences; the handedness as a mirror image; lambda^2 and dU/dlambda
under ["Ensemble","NVTlambda"]; and the input errors."""

import numpy as np
import pytest

import structmd

BOX = np.array([12.0, 12.0, 10.0])
PITCH, TURNS, RADIUS, INNER, K = 5.0, 2, 3.0, 1.5, 10.0
GRID = (24, 24, 20)

# Particles near the helix, inside and outside the tube, one across the periodic boundary in z; the
# offset keeps every coordinate off the grid's half cells, where the kernel's second derivative jumps
# (a central difference is then only first order).
POSITIONS = np.array([[3.0, 0.0, -5.0], [0.0, 3.9, -3.6], [-2.1, -1.0, 0.4], [1.0, -2.2, 4.9],
                      [4.5, 0.5, 2.0], [-3.0, 0.2, -4.95], [0.3, 0.4, 0.1]]) + np.array([0.0123, 0.0371, 0.0217])


def document(positions=POSITIONS, eps=1.0, lam=None, steps=None, **overrides):
    parameters = {"helixPitch": PITCH, "helixRadius": RADIUS, "eps": eps, "helixInnerRadius": INNER, "K": K,
                  "nTurns": TURNS, "nPointsHelix": 20, "nx": GRID[0], "ny": GRID[1], "nz": GRID[2]}
    parameters.update(overrides)
    ensemble = (["box", "temperature"], [list(BOX), 1.0]) if lam is None else \
        (["box", "temperature", "lambda"], [list(BOX), 1.0, lam])
    doc = {
        "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": "helix"}}},
        "global": {
            "types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"],
                      "data": [["A", 0.0, 0.5, 0.0]]},
            "ensemble": {"type": ["Ensemble", "NVT" if lam is None else "NVTlambda"], "labels": ensemble[0],
                         "data": [ensemble[1]]},
        },
        "integrator": {
            "vv": {"type": ["Verlet", "VelocityVerlet"], "parameters": {"timeStep": 0.001}},
            "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
                         "data": [[1, "vv", 10]]},
        },
        "state": {"labels": ["id", "position"], "data": [[i, list(map(float, p))] for i, p in enumerate(positions)]},
        "topology": {"structure": {"labels": ["id", "type"], "data": [[i, "A"] for i in range(len(positions))]},
                     "forceField": {"helix": {"type": ["External", "HelixBoundaries"], "parameters": parameters}}},
    }
    if steps:
        doc["simulationStep"] = steps
    return doc


def helix_distance(points, eps=1.0, samples=20000):
    """Distance from each point to the helix, by minimum image, from a dense sampling of the curve."""
    t = np.linspace(0.0, 2 * np.pi * TURNS, samples, endpoint=False)
    curve = np.stack([RADIUS * np.cos(t), eps * RADIUS * np.sin(t), PITCH * t / (2 * np.pi) - BOX[2] / 2], axis=1)
    out = np.empty(len(points))
    for k, p in enumerate(points):
        d = p - curve
        d -= BOX * np.round(d / BOX)
        out[k] = np.sqrt(np.min(np.sum(d * d, axis=1)))
    return out


def peskin(s):
    a = np.abs(s)
    inner = (1 + np.sqrt(np.clip(1 - 3 * a * a, 0, None))) / 3
    outer = (5 - 3 * a - np.sqrt(np.clip(1 - 3 * (1 - a) ** 2, 0, None))) / 6
    return np.where(a <= 0.5, inner, np.where(a <= 1.5, outer, 0.0))


def expected_energies(positions, eps=1.0):
    n = np.array(GRID)
    h = BOX / n
    index = np.stack(np.meshgrid(*[np.arange(m) for m in GRID], indexing="ij"), axis=-1).reshape(-1, 3)
    centres = (index + 0.5) * h - BOX / 2
    d = helix_distance(centres, eps)
    grid = np.where(d > INNER, 0.5 * K * (d - INNER) ** 2, 0.0).reshape(GRID)
    energies = []
    for p in positions:
        s = (p + BOX / 2) / h - 0.5
        nearest = np.floor(s + 0.5)
        cells = [nearest[a] + np.array([-1, 0, 1]) for a in range(3)]
        w = [peskin(s[a] - cells[a]) for a in range(3)]
        idx = [np.mod(cells[a].astype(int), GRID[a]) for a in range(3)]
        block = grid[np.ix_(idx[0], idx[1], idx[2])]
        energies.append(np.einsum("i,j,k,ijk->", w[0], w[1], w[2], block))
    return np.array(energies)


def test_energy_is_the_interpolated_tube_energy_of_the_distance_to_the_helix(options):
    expected = expected_energies(POSITIONS)
    with structmd.Simulation(options) as sim:
        sim.load(document())
        got = sim.particle_energies
    assert np.sum(expected > 1.0) >= 3 and np.sum(expected < 1e-9) >= 1, "inside and outside the tube"
    np.testing.assert_allclose(got, expected, rtol=1e-4, atol=1e-9)


def test_force_is_minus_the_gradient_of_the_energy(options):
    h = 1e-5
    with structmd.Simulation(options) as sim:
        sim.load(document())
        forces = sim.forces
        numerical = np.zeros_like(forces)
        for i in range(len(POSITIONS)):
            for a in range(3):
                energies = []
                for sign in (1, -1):
                    moved = POSITIONS.copy()
                    moved[i, a] += sign * h
                    sim.positions = moved
                    energies.append(sim.energy("helix"))
                numerical[i, a] = -(energies[0] - energies[1]) / (2 * h)
    assert np.max(np.abs(forces)) > 1.0
    np.testing.assert_allclose(forces, numerical, rtol=1e-6, atol=1e-6 * np.max(np.abs(forces)))


def test_a_left_handed_helix_is_the_mirror_image_of_the_right_handed_one(options):
    mirrored = POSITIONS * np.array([1.0, -1.0, 1.0])
    with structmd.Simulation(options) as right, structmd.Simulation(options) as left:
        right.load(document())
        left.load(document(positions=mirrored, eps=-1.0))
        assert left.particle_energies.sum() > 1.0
        # The grid's cell centres are symmetric under y -> -y, so the mirror image is exact.
        np.testing.assert_allclose(left.particle_energies, right.particle_energies, rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("lam", [0.0, 0.4, 1.0])
def test_the_field_scales_with_lambda_squared_and_dU_dlambda_is_2_lambda_U(options, tmp_path, lam):
    with structmd.Simulation(options) as full:
        full.load(document())
        u1 = full.energy("helix")
    path = tmp_path / "ti.dat"
    ti = {"ti": {"type": ["ThermodynamicMeasure", "ThermodynamicIntegration"],
                 "parameters": {"intervalStep": 1, "stepLambda": 10, "lambdaValues": [lam],
                                "outputFilePath": str(path)}}}
    with structmd.Simulation(options) as sim:
        sim.load(document(lam=lam, steps=ti))
        assert sim.energy("helix") == pytest.approx(lam * lam * u1, rel=1e-12, abs=1e-14)
        sim.step(1)
    derivative = float(path.read_text().splitlines()[2])
    assert derivative == pytest.approx(2 * lam * u1, rel=1e-10, abs=1e-12)


@pytest.mark.parametrize("override, path, message", [
    ({"eps": 0.5}, "parameters.eps", "right-handed"),
    ({"helixPitch": 4.0}, "parameters.helixPitch", "box height"),
    ({"helixRadius": 6.5}, "parameters.helixRadius", "half the box"),
    ({"nTurns": 0}, "parameters.nTurns", ""),
])
def test_bad_helix_parameters_name_their_path(options, override, path, message):
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.InputError) as error:
            sim.load(document(**override))
        assert f"topology.forceField.helix.{path}" in str(error.value) and message in str(error.value)
        sim.load(document())
