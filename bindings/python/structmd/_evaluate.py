"""One evaluation at positions given by a coupled code (the ASE calculator, the i-PI client): set the
box and the positions, compute, read energy, forces and virial. Everything in the input's units."""

from typing import NamedTuple

import numpy as np

from .constants import STATUS
from .errors import ArgumentError, UnsupportedError
from .simulation import Simulation

# The engine options of both couplings (ASE, i-PI) under what their caller gives: double precision,
# since optimisers and finite-difference checks on their side expect it, and a quiet log.
DEFAULT_OPTIONS = {"precision": "double", "log": "warning"}

# Off-diagonal cell entries below this fraction of the largest edge count as zero: cells that went
# through a unit conversion or a transpose keep exact zeros, but a tolerance costs nothing.
_TILT_TOLERANCE = 1e-12


class Evaluation(NamedTuple):
    energy: float  # the potential energy, structmd_get_energy "potential"
    forces: np.ndarray  # (n, 3), ascending particle id
    virial: np.ndarray  # 3x3, W = sum r_ij (x) F_ij (docs/c-api.md)


def orthorhombic_box(cell: np.ndarray) -> np.ndarray:
    """The edge lengths of a cell given as three lattice vectors (rows); UnsupportedError for a tilted
    cell, which structmd's rectangular boxes cannot represent, ArgumentError for a degenerate one."""
    cell = np.asarray(cell, dtype=np.float64).reshape(3, 3)
    lengths = np.diag(cell).copy()
    if not np.all(np.isfinite(cell)) or np.any(lengths <= 0.0):
        raise ArgumentError(STATUS["STRUCTMD_ERR_ARGUMENT"],
                            f"the cell must have positive finite edges along x, y and z, got {cell.tolist()}")
    off_diagonal = cell - np.diag(lengths)
    if np.abs(off_diagonal).max() > _TILT_TOLERANCE * lengths.max():
        raise UnsupportedError(STATUS["STRUCTMD_ERR_UNSUPPORTED"],
                               f"structmd's box is rectangular; the cell {cell.tolist()} is tilted")
    return lengths


def evaluate(sim: Simulation, positions: np.ndarray, box: np.ndarray) -> Evaluation:
    """Sets the box (only when it changed, since that rebuilds the neighbour lists) and then the
    positions, so that positions are taken as given rather than scaled with the box. The virial comes
    from the same pass over the force field as the forces, so it is always computed."""
    positions = np.asarray(positions, dtype=np.float64)
    n = sim.num_particles
    if positions.shape != (n, 3):
        raise ArgumentError(STATUS["STRUCTMD_ERR_ARGUMENT"],
                            f"the input has {n} particles, but {positions.shape[0]} positions came "
                            f"(shape {positions.shape})")
    if not np.array_equal(sim.box, box):
        sim.box = box
    sim.positions = positions
    sim.compute(forces=True, energy=True, virial=True)
    return Evaluation(sim.energy("potential"), sim.forces, sim.virial)
