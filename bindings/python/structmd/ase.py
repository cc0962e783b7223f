"""An ASE calculator over structmd: structmd.ase.Calculator(input) on an Atoms object whose atoms are
the input's particles, atom k being the particle of id k.

Units: ASE works in Å and eV. By default the input is taken to be in Å and eV too (then e.g. a
LennardJonesType1 entry with sigma in Å and epsilon in eV matches ase.calculators.lj.LennardJones).
An input in other units gives their size: length_unit is one input length in Å, energy_unit one input
energy in eV (an input in ["Units","KcalMol_A"]: length_unit=1, energy_unit=ase.units.kcal/ase.units.mol).

Each calculation sets the box (from the cell, when it changed) and the positions, then asks the engine
for forces, energy and the virial W (docs/c-api.md); stress = -W / volume,
in ASE's Voigt order (xx, yy, zz, yz, xz, xy). The cell must be rectangular and periodic in x, y and z,
as structmd's box is. Atomic numbers are not read: the input's types decide the interactions.
"""

import os
from typing import Any, List, Mapping, Optional, Sequence, Union

from ase.calculators.calculator import Calculator as _AseCalculator
from ase.calculators.calculator import all_changes
from ase.stress import full_3x3_to_voigt_6_stress

from ._evaluate import DEFAULT_OPTIONS, evaluate, orthorhombic_box
from .constants import STATUS
from .errors import UnsupportedError
from .simulation import Simulation

InputSource = Union[str, "os.PathLike[str]", Mapping[str, Any]]



class Calculator(_AseCalculator):
    """input: the structmd input (a path, a JSON document string or a dict); options: structmd_create
    options, merged over DEFAULT_OPTIONS (double precision, since ASE optimisers and finite-difference
    checks expect it); length_unit, energy_unit: the size of one input unit in Å and eV."""

    implemented_properties = ["energy", "free_energy", "forces", "stress"]
    nolabel = True

    def __init__(self, input: InputSource, options: Optional[Mapping[str, Any]] = None,
                 length_unit: float = 1.0, energy_unit: float = 1.0, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        if not (length_unit > 0.0 and energy_unit > 0.0):
            raise ValueError(f"length_unit and energy_unit must be positive, got {length_unit}, {energy_unit}")
        self.length_unit = float(length_unit)
        self.energy_unit = float(energy_unit)
        self.simulation = Simulation({**DEFAULT_OPTIONS, **(options or {})})
        try:
            self.simulation.load(input)
        except BaseException:
            self.simulation.close()
            raise

    def calculate(self, atoms: Any = None, properties: Optional[Sequence[str]] = None,
                  system_changes: List[str] = all_changes) -> None:
        """ASE's calculate: fills self.results with energy and free_energy (eV), forces (eV/Å, (n, 3))
        and stress (eV/Å^3, Voigt order) for atoms. Raises UnsupportedError for a non-periodic or
        tilted cell, ArgumentError for another number of atoms than the input's."""
        if properties is None:
            properties = self.implemented_properties
        super().calculate(atoms, properties, system_changes)
        atoms = self.atoms
        if not all(atoms.pbc):
            raise UnsupportedError(STATUS["STRUCTMD_ERR_UNSUPPORTED"],
                                   f"structmd is periodic in x, y and z; these Atoms have pbc={list(atoms.pbc)}")
        box = orthorhombic_box(atoms.cell.array) / self.length_unit
        result = evaluate(self.simulation, atoms.positions / self.length_unit, box)
        energy = result.energy * self.energy_unit
        self.results["energy"] = energy
        self.results["free_energy"] = energy
        self.results["forces"] = result.forces * (self.energy_unit / self.length_unit)
        stress = -result.virial * self.energy_unit / atoms.get_volume()
        self.results["stress"] = full_3x3_to_voigt_6_stress(stress)

    def close(self) -> None:
        """Releases the engine's handle; the calculator cannot calculate afterwards."""
        self.simulation.close()

    def __enter__(self) -> "Calculator":
        return self

    def __exit__(self, *exc_info: Any) -> None:
        self.close()

