"""Inputs written in Python: `Input` builds a UAMMD-structured document (docs/input-format.md) from
Python values and numpy arrays, section by section, and `Input.check()` has the engine itself read
it, so a wrong component, parameter or value is named by its JSON path before a run, by the same
reader a run uses (it cannot drift from the engine).

    from structmd import Input
    system = Input("lj", seed=1)
    system.add_type("A", mass=1.0)
    system.set_ensemble(box=10.0, temperature=1.0)
    system.add_particles(positions, types="A")
    system.add_interaction("nl", ["VerletConditionalListSet", "all"], {"cutOffVerletFactor": 1.12})
    system.add_interaction("lj", ["NonBonded", "LennardJonesType1"], {"cutOffFactor": 2.5, "condition": "all"},
                           labels=["name_i", "name_j", "epsilon", "sigma"], data=[["A", "A", 1.0, 1.0]])
    system.add_integrator("vv", ["Verlet", "VelocityVerlet"], {"timeStep": 0.005}, steps=1000)
    system.check()
    system.write("lj.json")           # or Simulation.load(system.document())

`Input.from_atoms(atoms)` starts one from an ASE Atoms object (types by chemical symbol, their
masses and charges, the box from the cell)."""

import json
from pathlib import Path
from typing import Any, Dict, List, Mapping, Optional, Sequence, Union

import numpy as np

Document = Dict[str, Any]
ComponentType = Sequence[str]
PathLike = Union[str, Path]

# Rows of "data" tables get a line each in text(); objects longer than this spread over lines.
LINE_WIDTH = 100


def _plain(value: Any) -> Any:
    """numpy arrays and scalars as the JSON values they stand for (lists, floats, ints, bools)."""
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, Mapping):
        return {str(key): _plain(item) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(item) for item in value]
    return value


def _component_type(kind: ComponentType) -> List[str]:
    pair = [str(word) for word in kind]
    if len(pair) != 2:
        raise ValueError(f"a component's type is [Class, SubClass], not {list(kind)!r}")
    return pair


def _entry(kind: ComponentType, parameters: Optional[Mapping[str, Any]], labels: Optional[Sequence[str]],
           data: Any) -> Document:
    """An entry {"type", "parameters", "labels", "data"}, with what was given, in the format's order."""
    if (labels is None) != (data is None):
        raise ValueError("a table needs both labels and data")
    entry: Document = {"type": _component_type(kind)}
    if parameters:
        entry["parameters"] = _plain(parameters)
    if labels is not None:
        entry["labels"] = [str(label) for label in labels]
        entry["data"] = _plain(data)
    return entry


def text(document: Document) -> str:
    """The document as JSON text for people: objects longer than a line spread over lines, each row of
    a table on its own. Raises TypeError for a value JSON cannot hold."""
    def written(value: Any, indent: int) -> str:
        pad, inner = "  " * indent, "  " * (indent + 1)
        items = []
        for key, item in value.items():
            if key == "data" and len(item) > 1:
                rows = (",\n" + inner + "  ").join(json.dumps(row) for row in item)
                items.append(f"{inner}{json.dumps(key)}: [\n{inner}  {rows}\n{inner}]")
            elif isinstance(item, dict) and len(json.dumps(item)) > LINE_WIDTH:
                items.append(f"{inner}{json.dumps(key)}: {written(item, indent + 1)}")
            else:
                items.append(f"{inner}{json.dumps(key)}: {json.dumps(item)}")
        return "{\n" + ",\n".join(items) + "\n" + pad + "}"
    return written(document, 0) + "\n"


class Input:
    """A UAMMD-structured document under construction. Each method adds to one section and checks
    what Python can see (shapes, names given twice, tables of one shape); `check()` has the engine
    judge the rest."""

    def __init__(self, name: str, seed: Optional[int] = None, units: Optional[str] = "None") -> None:
        """`name` and `seed`: the ["Simulation","Information"] entry (the engine's default seed when
        None); `units`: the ["Units", ...] subclass ("None", "KcalMol_A"), or None for no units entry."""
        parameters: Document = {"name": name}
        if seed is not None:
            parameters["seed"] = int(seed)
        self._system: Document = {"info": {"type": ["Simulation", "Information"], "parameters": parameters}}
        self._units = units
        self._types: List[List[Any]] = []
        self._ensemble: Optional[Document] = None
        self._state_labels: List[str] = []
        self._state: List[List[Any]] = []
        self._structure_labels: List[str] = []
        self._structure: List[List[Any]] = []
        self._force_field: Document = {}
        self._integrators: Document = {}
        self._schedule: List[List[Any]] = []
        self._steps: Document = {}

    # ---- global ------------------------------------------------------------------------------

    def add_type(self, name: str, mass: float = 1.0, radius: float = 0.5, charge: float = 0.0) -> None:
        """A row of ["Types","Basic"]: a particle type by name, its mass, radius and charge in the
        input's units. Raises ValueError for a name added before."""
        if any(row[0] == name for row in self._types):
            raise ValueError(f"type {name!r} is added twice")
        self._types.append([name, float(mass), float(radius), float(charge)])

    def set_ensemble(self, box: Union[float, Sequence[float], np.ndarray], temperature: float, kind: str = "NVT",
                     columns: Optional[Mapping[str, Any]] = None) -> None:
        """["Ensemble", kind] with the box (one edge for a cube, or three) and the temperature, and
        the other columns its kind takes (NVTlambda: {"lambda": 0.5}), in the input's units. An edge of
        0 or math.inf is an open (non-periodic) axis, written "inf" (JSON has no infinity). Raises
        ValueError for a box of other than one or three edges."""
        edges = np.asarray(box, dtype=float).ravel()
        if edges.size == 1:
            edges = np.repeat(edges, 3)
        if edges.size != 3:
            raise ValueError(f"the box is one edge or three, not {edges.size}")
        labels = ["box", "temperature", *(columns or {})]
        row = [["inf" if np.isinf(edge) else float(edge) for edge in edges], float(temperature), *(_plain(value) for value in (columns or {}).values())]
        self._ensemble = {"type": ["Ensemble", kind], "labels": labels, "data": [row]}

    # ---- particles ---------------------------------------------------------------------------

    def add_particles(self, positions: Any, types: Union[str, Sequence[str]], velocities: Any = None,
                      state_columns: Optional[Mapping[str, Any]] = None,
                      structure_columns: Optional[Mapping[str, Any]] = None) -> List[int]:
        """Particles with the next ids: `positions` (n, 3); `types` one name for all or one each;
        `velocities` (n, 3) or None (the engine draws them at the ensemble's temperature);
        `state_columns` more per-particle state ("direction", "magnetization", ...) and
        `structure_columns` per-particle topology ("chainId", "modelId", "batchId", ...), each an
        array of n values. Every call must give the same columns. Returns the ids given. Raises
        ValueError for a wrong shape or count, or columns other than the earlier particles'."""
        position_rows = np.asarray(positions, dtype=float)
        if position_rows.ndim != 2 or position_rows.shape[1] != 3:
            raise ValueError(f"positions must have shape (n, 3), not {position_rows.shape}")
        count = len(position_rows)
        names = [types] * count if isinstance(types, str) else [str(name) for name in types]
        if len(names) != count:
            raise ValueError(f"{len(names)} types for {count} particles")
        state = {"position": position_rows}
        if velocities is not None:
            state["velocity"] = np.asarray(velocities, dtype=float)
        state.update(state_columns or {})
        structure = dict(structure_columns or {})
        for label, column in (*state.items(), *structure.items()):
            if len(column) != count:
                raise ValueError(f"column {label!r} has {len(column)} values for {count} particles")
        state_labels = ["id", *state]
        structure_labels = ["id", "type", *structure]
        if self._state and (state_labels, structure_labels) != (self._state_labels, self._structure_labels):
            raise ValueError(f"these particles have columns {state_labels} and {structure_labels}, "
                             f"the earlier ones {self._state_labels} and {self._structure_labels}")
        self._state_labels, self._structure_labels = state_labels, structure_labels
        first = len(self._state)
        ids = list(range(first, first + count))
        state_values = [_plain(np.asarray(column)) for column in state.values()]
        structure_values = [_plain(np.asarray(column)) for column in structure.values()]
        for k, particle in enumerate(ids):
            self._state.append([particle, *(values[k] for values in state_values)])
            self._structure.append([particle, names[k], *(values[k] for values in structure_values)])
        return ids

    # ---- components --------------------------------------------------------------------------

    def add_interaction(self, name: str, kind: ComponentType, parameters: Optional[Mapping[str, Any]] = None,
                        labels: Optional[Sequence[str]] = None, data: Any = None) -> None:
        """A topology.forceField entry: a neighbour list, a pair term, bonds, a field, ... Raises
        ValueError for a name added before, a kind that is not [Class, SubClass], or labels without data."""
        self._add(self._force_field, "topology.forceField", name, _entry(kind, parameters, labels, data))

    def add_integrator(self, name: str, kind: ComponentType, parameters: Optional[Mapping[str, Any]] = None,
                       steps: Optional[int] = None) -> None:
        """An integrator entry; with `steps`, also the next row of the schedule (run after those before).
        Raises ValueError for a name added before, the name "schedule", or a kind not [Class, SubClass]."""
        if name == "schedule":
            raise ValueError("'schedule' is the schedule's own entry: pass steps= instead")
        self._add(self._integrators, "integrator", name, _entry(kind, parameters, None, None))
        if steps is not None:
            self._schedule.append([len(self._schedule) + 1, name, int(steps)])

    def add_step(self, name: str, kind: ComponentType, parameters: Optional[Mapping[str, Any]] = None,
                 labels: Optional[Sequence[str]] = None, data: Any = None) -> None:
        """A simulationStep entry: a measure, a writer, a flow-control step. Raises ValueError as
        add_interaction."""
        self._add(self._steps, "simulationStep", name, _entry(kind, parameters, labels, data))

    @staticmethod
    def _add(section: Document, where: str, name: str, entry: Document) -> None:
        if name in section:
            raise ValueError(f"{where}.{name} is added twice")
        section[name] = entry

    # ---- the document ------------------------------------------------------------------------

    def document(self) -> Document:
        """The document (a dict), sections in the format's order; sections with nothing in them left
        out. Raises nothing."""
        document: Document = {"system": self._system}
        global_section: Document = {}
        if self._units is not None:
            global_section["units"] = {"type": ["Units", self._units]}
        if self._types:
            global_section["types"] = {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"],
                                       "data": self._types}
        if self._ensemble is not None:
            global_section["ensemble"] = self._ensemble
        document["global"] = global_section
        if self._integrators:
            integrators = dict(self._integrators)
            if self._schedule:
                integrators["schedule"] = {"type": ["Schedule", "Integrator"],
                                           "labels": ["order", "integrator", "steps"], "data": self._schedule}
            document["integrator"] = integrators
        if self._state:
            document["state"] = {"labels": self._state_labels, "data": self._state}
        topology: Document = {}
        if self._structure:
            topology["structure"] = {"labels": self._structure_labels, "data": self._structure}
        if self._force_field:
            topology["forceField"] = self._force_field
        if topology:
            document["topology"] = topology
        if self._steps:
            document["simulationStep"] = self._steps
        return document

    def text(self) -> str:
        """The document as JSON for people (one table row a line)."""
        return text(self.document())

    def write(self, path: PathLike) -> None:
        """Writes the document as text() to the file path (UTF-8), replacing it. Raises OSError when it
        cannot be written."""
        Path(path).write_text(self.text(), encoding="utf-8")

    def check(self, options: Optional[Mapping[str, Any]] = None) -> None:
        """Loads the document into a throw-away Simulation (CPU, double precision unless `options`
        say otherwise): the engine's reader judges every component, parameter and value, and raises
        the StructmdError of the first problem (InputError naming its JSON path). Nothing is run, so
        no output is written."""
        from .simulation import Simulation
        with Simulation({"backend": "cpu", "precision": "double", "log": "quiet", **(options or {})}) as sim:
            sim.load(self.document())

    # ---- from ASE ----------------------------------------------------------------------------

    @classmethod
    def from_atoms(cls, atoms: Any, name: str = "ase", seed: Optional[int] = None, units: Optional[str] = None,
                   temperature: float = 0.0, length_unit: float = 1.0) -> "Input":
        """An Input of an ASE Atoms object: one type per chemical symbol (its atoms' mass and initial
        charge, radius 0.5), the box from an orthorhombic cell, the
        positions divided by `length_unit` (one input length in Å, as in structmd.ase). Interactions,
        integrators and steps are the caller's to add. Raises ValueError for a tilted or non-periodic
        cell, or atoms of one symbol with different masses or charges."""
        cell = np.asarray(atoms.cell, dtype=float)
        if np.any(np.abs(cell - np.diag(np.diag(cell))) > 1e-12 * max(1.0, float(np.abs(cell).max()))):
            raise ValueError("structmd's boxes are orthorhombic: the cell has off-diagonal terms")
        if np.any(np.diag(cell) <= 0.0):
            raise ValueError(f"the cell's diagonal must be positive (a periodic box), not {np.diag(cell).tolist()}")
        system = cls(name, seed=seed, units=units)
        symbols = atoms.get_chemical_symbols()
        masses = atoms.get_masses()
        charges = atoms.get_initial_charges()
        for symbol in dict.fromkeys(symbols):
            mine = [k for k, other in enumerate(symbols) if other == symbol]
            # A type holds one mass and one charge: atoms of a symbol that differ need types of their own.
            for what, values in (("masses", masses), ("charges", charges)):
                if np.ptp(values[mine]) != 0.0:
                    raise ValueError(f"the {symbol} atoms have different {what}; a type has one")
            system.add_type(symbol, mass=float(masses[mine[0]]), charge=float(charges[mine[0]]))
        system.set_ensemble(np.diag(cell) / length_unit, temperature)
        system.add_particles(np.asarray(atoms.positions) / length_unit, symbols)
        return system
