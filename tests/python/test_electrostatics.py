"""["LongRange","Electrostatics"] through the whole engine, against sums written independently in
tests/reference/electrostatics_reference.py: the exact Fourier sum of Gaussian charges, the classic
Ewald sum of point charges and OpenMM's PME; forces against central differences of the energy across
the periodic boundary; units, the split's irrelevance, a non-neutral box, and bad input. Run on the
cuda backend by python_electrostatics_cuda (cuFFT)."""

import math
import os
import sys

import numpy as np
import pytest

import structmd

sys.path.insert(0, os.path.join(os.path.dirname(__file__), os.pardir, "reference"))
import electrostatics_reference as ref  # noqa: E402

BOX = np.array([6.0, 6.5, 7.0])


def load(options, positions, charges, parameters, units="None", box=BOX):
    sim = structmd.Simulation(dict(options, precision="double"))
    sim.load(ref.document(positions, charges, box, parameters, units))
    return sim


def measured(options, positions, charges, parameters, **kwargs):
    with load(options, positions, charges, parameters, **kwargs) as sim:
        return sim.energy("elec"), sim.forces


@pytest.mark.parametrize("tolerance", [1e-4, 1e-6])
def test_gaussian_charges_match_the_exact_fourier_sum(options, tolerance):
    positions, charges = ref.random_neutral_system(40, BOX, seed=5)
    exact = ref.gaussian_spectral(positions, charges, BOX, 0.4)
    energy, forces = measured(options, positions, charges,
                              {"dielectricConstant": 1.0, "gaussianWidth": 0.4, "tolerance": tolerance})
    force_error, energy_error = ref.errors(forces, energy, exact)
    assert force_error < tolerance, f"force error {force_error:.2e}"
    assert energy_error < tolerance, f"energy error {energy_error:.2e}"


@pytest.mark.parametrize("tolerance", [1e-4, 1e-6])
def test_point_charges_match_the_ewald_sum(options, tolerance):
    positions, charges = ref.random_neutral_system(40, BOX, seed=6)
    exact = ref.point_ewald(positions, charges, BOX)
    energy, forces = measured(options, positions, charges,
                              {"dielectricConstant": 1.0, "gaussianWidth": 0.0, "tolerance": tolerance})
    force_error, energy_error = ref.errors(forces, energy, exact)
    assert force_error < tolerance, f"force error {force_error:.2e}"
    assert energy_error < tolerance, f"energy error {energy_error:.2e}"


@pytest.mark.parametrize("precision", ["single", "mixed"])
def test_single_and_mixed_precision_reach_a_loose_tolerance(options, precision):
    positions, charges = ref.random_neutral_system(40, BOX, seed=5)
    exact = ref.gaussian_spectral(positions, charges, BOX, 0.3)
    with structmd.Simulation(dict(options, precision=precision)) as sim:
        sim.load(ref.document(positions, charges, BOX, {"dielectricConstant": 1.0, "gaussianWidth": 0.3,
                                                         "tolerance": 1e-4, "splitThreshold": 3.0}))
        force_error, energy_error = ref.errors(np.asarray(sim.forces, float), sim.energy("elec"), exact)
    assert force_error < 1e-4 and energy_error < 1e-4, f"force {force_error:.2e}, energy {energy_error:.2e}"


def test_point_charges_match_openmm_pme(options):
    pytest.importorskip("openmm")
    positions, charges = ref.random_neutral_system(50, BOX, seed=7)
    openmm = ref.openmm_pme(positions, charges, BOX)
    energy, forces = measured(options, positions, charges,
                              {"dielectricConstant": 1.0, "gaussianWidth": 0.0, "tolerance": 1e-6})
    force_error, energy_error = ref.errors(forces, energy, openmm)
    assert force_error < 1e-6 and energy_error < 1e-6, f"force {force_error:.2e}, energy {energy_error:.2e}"


@pytest.mark.parametrize("width", [0.0, 0.3])
def test_force_is_minus_the_energy_gradient_across_the_boundary(options, width):
    """Charges clustered about the x = +-L/2 face, the pair term acting (the split is set)."""
    parameters = {"dielectricConstant": 2.0, "gaussianWidth": width, "tolerance": 1e-5, "splitThreshold": 2.0}
    for seed in range(8, 100):  # the first configuration where no pair crosses the cutoff in a difference step
        rng = np.random.default_rng(seed)
        positions, charges = ref.random_neutral_system(16, BOX, seed=seed)
        positions[:, 0] = BOX[0] / 2 + rng.uniform(-1.0, 1.0, len(positions))
        positions -= BOX * np.round(positions / BOX)
        _, cutoff, _ = ref.chosen_split_and_grid(charges, BOX, width, 1e-5, split=2.0)
        d = positions[:, None, :] - positions[None, :, :]
        r = np.linalg.norm(d - BOX * np.round(d / BOX), axis=2)
        if np.min(np.abs(r - cutoff)) > 1e-3:
            break
    assert 0.0 < cutoff < np.min(r[r > 0]) + 3.0 and np.sum((r > 0) & (r < cutoff)) > 0, "the pair term must act"
    with load(options, positions, charges, parameters) as sim:
        forces = sim.forces
        h = 1e-5
        numerical = np.zeros_like(forces)
        for i in range(len(positions)):
            for a in range(3):
                moved = positions.copy()
                moved[i, a] += h
                sim.positions = moved
                up = sim.energy("elec")
                moved[i, a] -= 2 * h
                sim.positions = moved
                down = sim.energy("elec")
                numerical[i, a] = -(up - down) / (2 * h)
    error = np.max(np.abs(forces - numerical)) / np.max(np.abs(numerical))
    assert error < 1e-6, f"relative error {error:.2e}"


def test_the_split_changes_nothing_but_rounding(options):
    """The Ewald split is a way of summing: with and without a pair term the sum is the same."""
    positions, charges = ref.random_neutral_system(30, BOX, seed=9)
    base = {"dielectricConstant": 1.0, "gaussianWidth": 0.25, "tolerance": 1e-6}
    spectral = measured(options, positions, charges, dict(base, splitThreshold=1e6))  # s = w: mesh only
    split = measured(options, positions, charges, dict(base, splitThreshold=2.5))
    assert abs(spectral[0] - split[0]) < 1e-6 * abs(spectral[0])
    assert np.max(np.abs(spectral[1] - split[1])) < 1e-5 * np.max(np.abs(spectral[1]))


def test_a_charged_box_has_a_neutralising_background(options):
    """Without neutrality the k = 0 term stays out, whatever the split: the exact sum's convention."""
    positions, charges = ref.random_neutral_system(30, BOX, seed=10)
    charges = charges + 0.3
    exact = ref.gaussian_spectral(positions, charges, BOX, 0.3)
    for split in (0.0, 3.0):
        energy, forces = measured(options, positions, charges, {"dielectricConstant": 1.0, "gaussianWidth": 0.3,
                                                                "tolerance": 1e-6, "splitThreshold": split})
        force_error, energy_error = ref.errors(forces, energy, exact)
        # A split the input forces meets the tolerance to within a factor 2 (the rules are tuned for their own).
        assert force_error < 2e-6 and energy_error < 1e-6, f"split {split}: {force_error:.2e}, {energy_error:.2e}"


def test_units_and_dielectric_scale_the_coulomb_constant(options):
    """k_e = f / eps_r: KcalMol_A's electric conversion 332.0716 over the dielectric constant."""
    positions, charges = ref.random_neutral_system(20, BOX, seed=12)
    parameters = {"dielectricConstant": 1.0, "gaussianWidth": 0.4, "tolerance": 1e-6}
    plain = measured(options, positions, charges, parameters)
    water = measured(options, positions, charges, dict(parameters, dielectricConstant=78.5), units="KcalMol_A")
    exact = ref.gaussian_spectral(positions, charges, BOX, 0.4, k_e=332.0716 / 78.5)
    assert abs(water[0] - exact[0]) < 1e-6 * abs(exact[0])
    assert np.allclose(water[1], plain[1] * 332.0716 / 78.5, rtol=1e-9, atol=0)


@pytest.mark.parametrize("split", [0.0, 3.0])
def test_virial_matches_the_strain_derivative(options, split):
    """Against the exact sum's virial, with the pair term (split 3) and without (mesh only), in a charged box."""
    positions, charges = ref.random_neutral_system(30, BOX, seed=15)
    charges = charges + 0.2
    exact = ref.gaussian_spectral_virial(positions, charges, BOX, 0.3)
    for a in range(3):  # the reference itself: W_aa = -dU/d(strain_aa), the box stretched along a
        def stretched(e):
            scale = np.eye(3)[a] * e + 1.0
            return ref.gaussian_spectral(positions * scale, charges, BOX * scale, 0.3)[0]
        assert abs(exact[a, a] + (stretched(1e-6) - stretched(-1e-6)) / 2e-6) < 1e-7 * np.max(np.abs(exact))
    with load(options, positions, charges, {"dielectricConstant": 1.0, "gaussianWidth": 0.3, "tolerance": 1e-6,
                                            "splitThreshold": split}) as sim:
        virial = sim.virial
    assert np.max(np.abs(virial - exact)) < 1e-5 * np.max(np.abs(exact)), f"{virial} against {exact}"


def test_steps_conserve_energy(options):
    positions, charges = ref.random_neutral_system(30, BOX, seed=13, minimum=0.8)
    doc = ref.document(positions, charges, BOX, {"dielectricConstant": 1.0, "gaussianWidth": 0.3,
                                                 "tolerance": 1e-6})
    doc["integrator"]["vv"]["parameters"]["timeStep"] = 0.002
    doc["integrator"]["schedule"]["data"] = [[1, "vv", 500]]
    with structmd.Simulation(dict(options, precision="double")) as sim:
        sim.load(doc)
        start = sim.energy("elec") + 0.5 * np.sum(sim.velocities ** 2)  # unit masses
        sim.run()
        kinetic = 0.5 * np.sum(sim.velocities ** 2)
        assert sim.step_number == 500 and kinetic > 1e-3, "the charges must move"
        drift = abs(sim.energy("elec") + kinetic - start)
        assert drift < 1e-5 * kinetic, f"energy drift {drift:.2e} against kinetic {kinetic:.2e}"


@pytest.mark.parametrize("key, value, message", [
    ("tolerance", 2.0, "parameters.tolerance: expected a number below 1"),
    ("tolerance", 1e-14, "parameters.tolerance: the mesh would need"),
    ("gaussianWidth", -1.0, "parameters.gaussianWidth"),
    ("dielectricConstant", 0.0, "parameters.dielectricConstant"),
    ("splitThreshold", 0.05, "parameters.splitThreshold: the pair term's cutoff"),
])
def test_bad_parameters_name_their_path(options, key, value, message):
    positions, charges = ref.random_neutral_system(8, BOX, seed=14)
    parameters = {"dielectricConstant": 1.0, "gaussianWidth": 0.4}
    parameters[key] = value
    with structmd.Simulation(options) as sim, pytest.raises(structmd.InputError, match=message.replace(".", r"\.")):
        sim.load(ref.document(positions, charges, BOX, parameters))


def test_a_missing_width_is_an_input_error(options):
    positions, charges = ref.random_neutral_system(8, BOX, seed=14)
    with structmd.Simulation(options) as sim, pytest.raises(structmd.InputError, match="gaussianWidth"):
        sim.load(ref.document(positions, charges, BOX, {"dielectricConstant": 1.0}))
