"""structmd.ase.Calculator against ASE's own Lennard-Jones calculator (ase.calculators.lj, shifted
energy, cutoff rc) on a rattled fcc argon crystal: energy, forces and stress must agree to rounding,
also after the positions and the cell change, and with an input in reduced units mapped through
length_unit and energy_unit."""

import numpy as np
import pytest
from ase.calculators.lj import LennardJones

import structmd
from structmd.ase import Calculator
from systems import CUTOFF_FACTOR, EPSILON, SIGMA, lj_input, rattled_argon

def ase_reference(atoms):
    reference = atoms.copy()
    reference.calc = LennardJones(sigma=SIGMA, epsilon=EPSILON, rc=CUTOFF_FACTOR * SIGMA)
    return reference.get_potential_energy(), reference.get_forces(), reference.get_stress()


def assert_matches_ase(atoms):
    energy, forces, stress = ase_reference(atoms)
    assert atoms.get_potential_energy() == pytest.approx(energy, rel=1e-11)
    assert atoms.get_potential_energy(force_consistent=True) == pytest.approx(energy, rel=1e-11)
    force_scale = np.abs(forces).max()
    assert force_scale > 1e-3  # the rattle makes forces a real test
    np.testing.assert_allclose(atoms.get_forces(), forces, rtol=0, atol=1e-11 * force_scale)
    np.testing.assert_allclose(atoms.get_stress(), stress, rtol=0, atol=1e-11 * np.abs(stress).max())


def test_energy_forces_and_stress_match_ase_lennard_jones(options):
    atoms = rattled_argon(seed=1)
    with Calculator(lj_input(atoms), options=options) as calc:
        atoms.calc = calc
        assert_matches_ase(atoms)


def test_new_positions_and_a_new_cell_are_followed(options):
    atoms = rattled_argon(seed=2)
    with Calculator(lj_input(atoms), options=options) as calc:
        atoms.calc = calc
        assert_matches_ase(atoms)
        atoms.rattle(stdev=0.05, seed=3)
        assert_matches_ase(atoms)
        atoms.set_cell(atoms.cell * 1.03, scale_atoms=True)
        assert_matches_ase(atoms)


def test_reduced_units_are_mapped_through_length_and_energy_units(options):
    atoms = rattled_argon(seed=4)
    reduced = lj_input(atoms, sigma=1.0, epsilon=1.0, length_unit=SIGMA)
    with Calculator(reduced, options=options, length_unit=SIGMA, energy_unit=EPSILON) as calc:
        atoms.calc = calc
        assert_matches_ase(atoms)


def test_a_wrong_number_of_atoms_is_refused(options):
    atoms = rattled_argon(seed=5)
    with Calculator(lj_input(atoms), options=options) as calc:
        fewer = atoms[:-1]
        fewer.calc = calc
        with pytest.raises(structmd.ArgumentError, match=f"{len(atoms)} particles"):
            fewer.get_forces()


def test_a_tilted_or_open_cell_is_refused(options):
    atoms = rattled_argon(seed=6)
    with Calculator(lj_input(atoms), options=options) as calc:
        tilted = atoms.copy()
        tilted.cell[1, 0] = 0.5
        tilted.calc = calc
        with pytest.raises(structmd.UnsupportedError, match="tilted"):
            tilted.get_forces()
        open_z = atoms.copy()
        open_z.pbc = [True, True, False]
        open_z.calc = calc
        with pytest.raises(structmd.UnsupportedError, match="pbc"):
            open_z.get_forces()


def test_bad_input_raises_input_error(options):
    with pytest.raises(structmd.InputError):
        Calculator({"system": {}}, options=options)
