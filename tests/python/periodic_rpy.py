"""Shared references for the triply periodic hydrodynamics tests (force coupling method and
positively split Ewald), written here independently of the engine:
- Hasimoto's (J. Fluid Mech. 5, 317 (1959)) self-mobility of a sphere in a cubic lattice,
  mu(L) = (1 - 2.837297 a/L + (4 pi / 3) (a/L)^3 + O((a/L)^6)) / (6 pi eta a).
- The periodic Rotne-Prager-Yamakawa mobility by Beenakker's Ewald sum (J. Chem. Phys. 85, 1581
  (1986)), and its overlapping form (Wajnryb et al. 2013) for pairs closer than 2a.
- The input document of a few equal spheres in a periodic box under one integrator entry, and the
  mobility measured from that integrator's deterministic steps.
- The check that a bad entry is refused at load with its JSON path.
"""

import math
import re

import numpy as np
import pytest

import structmd

ETA = 1.3
RADIUS = 1.0
HASIMOTO = 2.837297
MU0 = 1.0 / (6.0 * math.pi * ETA * RADIUS)


def document(positions, box, entry, steps=1, temperature=0.0, force_field=None, seed=7, batches=None):
    """One type A of radius RADIUS at `positions`, integrated by `entry`; `batches`: a batchId by particle."""
    box = [float(b) for b in (box if np.ndim(box) else [box] * 3)]
    structure = {"labels": ["id", "type"], "data": [[i, "A"] for i in range(len(positions))]}
    if batches is not None:
        structure = {"labels": ["id", "type", "batchId"], "data": [[i, "A", b] for i, b in enumerate(batches)]}
    return {
        "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": "periodic-bdhi", "seed": seed}}},
        "global": {
            "types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"],
                      "data": [["A", 1.0, RADIUS, 0.0]]},
            "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"], "data": [[box, temperature]]},
        },
        "integrator": {"bd": entry, "schedule": {"type": ["Schedule", "Integrator"],
                                                 "labels": ["order", "integrator", "steps"], "data": [[1, "bd", steps]]}},
        "state": {"labels": ["id", "position"], "data": [[i, [float(c) for c in p]] for i, p in enumerate(positions)]},
        "topology": {"structure": structure, "forceField": force_field or {}},
    }


def assert_refused_at_load(options, doc, path, message=""):
    """Loading doc raises InputError naming the JSON path, then saying message (a regular expression)."""
    with structmd.Simulation(options) as sim:
        with pytest.raises(structmd.InputError, match=re.escape(path) + ".*" + message):
            sim.load(doc)


def assert_checkpoint_carries_the_fluid(options, entry, path):
    """At kT = 0 a particle pulled in a box of side 8 moves with the flow built up so far: a run continued
    from a checkpoint saved after 20 steps matches the uninterrupted one bit for bit only if the fluid
    was saved and restored with it."""
    with structmd.Simulation(options) as sim:
        sim.load(document([[0.3, 0.1, -0.2]], 8.0, entry, steps=10 ** 6))
        sim.external_forces = np.array([[1e-3, 0.0, 0.0]])
        sim.step(20)
        sim.save_checkpoint(path)
        sim.step(20)
        straight = sim.positions.copy()
        sim.load_checkpoint(path)
        sim.step(20)
        assert np.array_equal(sim.positions, straight)


def with_open_z(doc):
    """doc with its box open along z (an infinite edge)."""
    doc["global"]["ensemble"]["data"][0][0][2] = "inf"
    return doc


def minimum_image(d, box):
    return d - box * np.round(d / box)


def measured_mobility(options, positions, box, entry, time_step):
    """M (3N x 3N) from the integrator's step at temperature 0: column (j, axis) is the displacement
    of every particle under a unit force on j along that axis, over dt."""
    positions = np.asarray(positions, float)
    n = len(positions)
    box = np.asarray(box if np.ndim(box) else [box] * 3, float)
    mobility = np.zeros((3 * n, 3 * n))
    with structmd.Simulation(options) as sim:
        sim.load(document(positions, box, entry, steps=10 ** 6))
        start = sim.positions
        for column in range(3 * n):
            force = np.zeros((n, 3))
            force.flat[column] = 1.0
            sim.positions = start
            sim.external_forces = force
            sim.step(1)
            mobility[:, column] = minimum_image(sim.positions - start, box).ravel() / time_step
    return mobility


def rpy_ewald(positions, a, eta, box, xi, real_images=3):
    """The periodic RPY mobility (3N x 3N, particles at least 2a apart) by Beenakker's Ewald sum with
    splitting parameter xi."""
    pos = np.asarray(positions, float)
    n = len(pos)
    box = np.asarray(box, float)
    mu0 = 1.0 / (6.0 * math.pi * eta * a)
    root_pi = math.sqrt(math.pi)
    span = range(-real_images, real_images + 1)
    images = np.array([[i, j, k] for i in span for j in span for k in span], float) * box
    mobility = np.zeros((3 * n, 3 * n))
    for i in range(n):
        for j in range(n):
            block = np.zeros((3, 3))
            for image in images:
                r = pos[i] - pos[j] + image
                d = np.linalg.norm(r)
                if d == 0.0:
                    continue
                gauss, tail = math.exp(-xi * xi * d * d) / root_pi, math.erfc(xi * d)
                f = tail * (0.75 * a / d + 0.5 * a ** 3 / d ** 3) + gauss * (
                    4 * xi ** 7 * a ** 3 * d ** 4 + 3 * xi ** 3 * a * d ** 2 - 20 * xi ** 5 * a ** 3 * d ** 2
                    - 4.5 * xi * a + 14 * xi ** 3 * a ** 3 + xi * a ** 3 / d ** 2)
                g = tail * (0.75 * a / d - 1.5 * a ** 3 / d ** 3) + gauss * (
                    -4 * xi ** 7 * a ** 3 * d ** 4 - 3 * xi ** 3 * a * d ** 2 + 16 * xi ** 5 * a ** 3 * d ** 2
                    + 1.5 * xi * a - 2 * xi ** 3 * a ** 3 - 3 * xi * a ** 3 / d ** 2)
                unit = r / d
                block += mu0 * (f * np.eye(3) + g * np.outer(unit, unit))
            if i == j:
                block += mu0 * (1 - 6 * xi * a / root_pi + 40 * xi ** 3 * a ** 3 / (3 * root_pi)) * np.eye(3)
            mobility[3 * i:3 * i + 3, 3 * j:3 * j + 3] = block
    volume = box.prod()
    waves, k2 = wave_vectors(box, 2.0 * xi * math.sqrt(36.0 * math.log(10.0)))
    amplitude = ((1 - a * a * k2 / 3) * (1 + k2 / (4 * xi * xi) + k2 * k2 / (8 * xi ** 4))
                 * np.exp(-k2 / (4 * xi * xi)) / k2 / (eta * volume))
    add_wave_sum(mobility, pos, waves, k2, amplitude)
    return mobility


def rpy_overlap_correction(positions, a, eta, box):
    """What the overlapping RPY form adds to rpy_ewald (which uses the far form for every image) for
    the pairs closer than 2a (nearest images; the boxes here are larger than 4a):
      M = mu0 [(1 - 9 r / (32 a)) I + 3 r / (32 a) r^ r^]   against
      M = (1 / (8 pi eta r)) [(1 + 2 a^2 / (3 r^2)) I + (1 - 2 a^2 / r^2) r^ r^]."""
    pos = np.asarray(positions, float)
    box = np.asarray(box, float)
    mu0 = 1.0 / (6.0 * math.pi * eta * a)
    correction = np.zeros((3 * len(pos), 3 * len(pos)))
    for i in range(len(pos)):
        for j in range(len(pos)):
            r = minimum_image(pos[i] - pos[j], box)
            d = np.linalg.norm(r)
            if i == j or d >= 2 * a:
                continue
            unit = np.outer(r, r) / (d * d)
            overlapping = mu0 * ((1 - 9 * d / (32 * a)) * np.eye(3) + 3 * d / (32 * a) * unit)
            far = ((1 + 2 * a * a / (3 * d * d)) * np.eye(3) + (1 - 2 * a * a / (d * d)) * unit) / (8 * math.pi * eta * d)
            correction[3 * i:3 * i + 3, 3 * j:3 * j + 3] = overlapping - far
    return correction


def wave_vectors(box, cut):
    axes = [2 * math.pi * np.arange(-m, m + 1) / length
            for m, length in ((int(math.ceil(cut * length / (2 * math.pi))), length) for length in box)]
    waves = np.stack(np.meshgrid(*axes, indexing="ij"), -1).reshape(-1, 3)
    k2 = (waves * waves).sum(1)
    keep = (k2 > 0) & (k2 < cut * cut)
    return waves[keep], k2[keep]


def add_wave_sum(mobility, pos, waves, k2, amplitude):
    projector = np.eye(3)[None] - waves[:, :, None] * waves[:, None, :] / k2[:, None, None]
    for i in range(len(pos)):
        for j in range(len(pos)):
            phase = np.cos(waves @ (pos[i] - pos[j]))
            mobility[3 * i:3 * i + 3, 3 * j:3 * j + 3] += np.einsum("k,kab->ab", amplitude * phase, projector)


def hasimoto(a, length):
    return MU0 * (1 - HASIMOTO * a / length + (4 * math.pi / 3) * (a / length) ** 3)


def windowed_msd(sim, windows, lag, length):
    """The mean square displacement over `lag` steps of a running simulation, from `windows`
    consecutive non-overlapping windows of the unwrapped trajectories (each window's particles
    averaged first, since the fluid correlates them), and its standard error from the windows' spread."""
    previous = sim.positions
    unwrapped = previous.copy()
    window_msd = []
    for _ in range(windows):
        start = unwrapped.copy()
        for _ in range(lag):
            sim.step(1)
            now = sim.positions
            unwrapped += minimum_image(now - previous, length)
            previous = now
        window_msd.append(np.mean(np.sum((unwrapped - start) ** 2, axis=1)))
    window_msd = np.array(window_msd)
    return window_msd.mean(), window_msd.std(ddof=1) / math.sqrt(windows)


def diffusion_from_msd_slopes(trajectory, time_step, lag, windows=8):
    """The long-time diffusion coefficient of an unwrapped trajectory (steps x particles x 3): in each
    of `windows` consecutive windows, the slope of the mean square displacement between lags `lag`
    and 2 `lag` (steps), over 6 dt; their mean and its standard error from their spread (the fluid
    correlates the particles, so windows, not particles, are the samples)."""
    slopes = []
    for window in np.array_split(np.arange(len(trajectory)), windows):
        part = trajectory[window]
        msd = [np.mean(np.sum((part[k:] - part[:-k]) ** 2, axis=-1)) for k in (lag, 2 * lag)]
        slopes.append((msd[1] - msd[0]) / (6 * lag * time_step))
    slopes = np.array(slopes)
    return slopes.mean(), slopes.std(ddof=1) / math.sqrt(windows)


def trapped_particle_energy(options, entry, box, kT, stiffness, time_step):
    """A particle in a harmonic trap of stiffness K under the integrator `entry`: <K x^2> per axis
    from samples one relaxation time apart (with the self-mobility mu, Hasimoto's), in 20 blocks.
    Returns (measured, its standard error, Euler-Maruyama's exact kT / (1 - mu K dt / 2))."""
    trap = {"trap": {"type": ["Bond1", "FixedHarmonic"], "labels": ["id_i", "K", "r0", "position"],
                     "data": [[0, stiffness, 0.0, [0.0, 0.0, 0.0]]]}}
    mobility = hasimoto(RADIUS, box)
    stride = int(math.ceil(1.0 / (mobility * stiffness * time_step)))
    with structmd.Simulation(options) as sim:
        sim.load(document([[0.0, 0.0, 0.0]], box, entry, steps=10 ** 7, temperature=kT, force_field=trap))
        samples = []
        for _ in range(400):
            sim.step(stride)
            samples.append(sim.positions[0].copy())
    energy = stiffness * np.array(samples) ** 2
    blocks = energy.reshape(20, -1, 3).mean(axis=(1, 2))
    expected = kT / (1.0 - 0.5 * mobility * stiffness * time_step)
    return blocks.mean(), blocks.std(ddof=1) / math.sqrt(len(blocks)), expected


def noise_samples(options, positions, box, entry, kT, samples):
    """The displacements (samples x 3N) of many single steps from the same configuration, reset
    before each, with no force: the noise alone (and a drift where the mobility has a divergence)."""
    moves = np.empty((samples, 3 * len(positions)))
    with structmd.Simulation(options) as sim:
        sim.load(document(positions, box, entry, steps=10 ** 7, temperature=kT))
        start = sim.positions
        for s in range(samples):
            sim.positions = start
            sim.step(1)
            moves[s] = minimum_image(sim.positions - start, np.asarray(box, float)).ravel()
    return moves


def covariance_standard_error(expected, samples):
    """The standard error of each element of the sample covariance of n Gaussian vectors whose
    covariance is `expected`: sqrt((C_aa C_bb + C_ab^2) / n)."""
    return np.sqrt((np.outer(np.diag(expected), np.diag(expected)) + expected ** 2) / samples)
