"""["BDHIDoublyPeriodic","DPStokes"]: Brownian dynamics with hydrodynamic interactions in a fluid
periodic along x and y, open along z ("none"), above a no-slip wall at z = -H/2 ("bottom") or
between walls at z = -H/2 and H/2 ("slit") (docs/input-format.md).

References written here, independent of the engine:
- Open ("none"): the doubly periodic Stokes mobility of Gaussian blobs (sigma = a / sqrt(pi)) from
  the 3D Oseen tensor in Fourier space, the sum over the plane's wave vectors k != 0 (k = 0 left
  out: no net flow, UAMMD's convention) of the integral over q_z done numerically,
    M_ab(r) = 1/(eta A) sum_k int dq_z/(2 pi) exp(i q.r) exp(-q^2 sigma^2) (delta_ab - q_a q_b / q^2) / q^2.
- Bottom wall: the Rotne-Prager-Blake self mobility of Swan & Brady (Phys. Fluids 19, 113306
  (2007)) at height h (lambda = a / h),
    mu_par / mu0 = 1 - 9/16 lambda + 1/8 lambda^3 - 1/16 lambda^5,
    mu_perp / mu0 = 1 - 9/8 lambda + 1/2 lambda^3 - 1/8 lambda^5,
  after removing the periodic images: the plane's mean flow (the fluid above the forces moving as a
  plug, (h - sigma/sqrt(pi)) / (eta A) for a Gaussian at height h, exactly) and then the rest,
  which falls as 1/L^3, extrapolated from two box sizes.
- Slit: Faxen's mobility of a sphere midway between two walls a distance 2l apart (Happel & Brenner,
  section 7-4), mu / mu0 = 1 - 1.004 lambda + 0.418 lambda^3 + 0.21 lambda^4 - 0.169 lambda^5,
  lambda = a / l, after removing the plane's mean flow (Couette's, l/2 / (eta A) at the middle) and
  the images (extrapolated as above).

The mobility is read column by column from the integrator's own deterministic step at temperature 0
(periodic_rpy.measured_mobility): a force F on one particle along one axis moves every particle by
dt M F.
"""

import math

import numpy as np
import pytest

import periodic_rpy
import structmd

ETA = periodic_rpy.ETA
RADIUS = periodic_rpy.RADIUS
MU0 = periodic_rpy.MU0
SIGMA = RADIUS / math.sqrt(math.pi)


# ---- input documents ------------------------------------------------------------------------------

def dpstokes(length, height, n, mode, time_step=0.01, nz=None, **extra):
    parameters = {"timeStep": time_step, "viscosity": ETA, "hydrodynamicRadius": RADIUS, "nx": n, "ny": n,
                  "Lx": length, "Ly": length, "H": height, "w": 6, "mode": mode, "nz": nz, **extra}
    return {"type": ["BDHIDoublyPeriodic", "DPStokes"],
            "parameters": {k: v for k, v in parameters.items() if v is not None}}


def box_of(length, height):
    """The simulation box: the slab's plane, and z periodic far beyond the slab."""
    return [length, length, 2.0 * height]


def mobility(options, positions, length, height, n, mode, **extra):
    time_step = extra.pop("time_step", 0.01)
    return periodic_rpy.measured_mobility(options, positions, box_of(length, height),
                                          dpstokes(length, height, n, mode, time_step=time_step, **extra), time_step)


def document(positions, length, height, entry, **rest):
    return periodic_rpy.document(positions, box_of(length, height), entry, **rest)


# ---- independent references -----------------------------------------------------------------------

def open_mobility(positions, length, a=RADIUS, eta=ETA):
    """The doubly periodic open mobility (3N x 3N) by the Fourier sum over k and quadrature over q_z."""
    sigma = a / math.sqrt(math.pi)
    pos = np.asarray(positions, float)
    cut = 7.0 / sigma
    m = int(math.ceil(cut * length / (2 * math.pi)))
    axis = 2 * math.pi * np.arange(-m, m + 1) / length
    kx, ky = [c.ravel() for c in np.meshgrid(axis, axis, indexing="ij")]
    keep = (kx * kx + ky * ky > 0) & (kx * kx + ky * ky < cut * cut)
    kx, ky = kx[keep], ky[keep]
    qz, dq = np.linspace(-cut, cut, 2801, retstep=True)
    q = [kx[:, None] + 0 * qz, ky[:, None] + 0 * qz, qz[None, :] + 0 * kx[:, None]]
    q2 = q[0] ** 2 + q[1] ** 2 + q[2] ** 2
    weight = np.exp(-q2 * sigma * sigma) / q2 * dq / (2 * math.pi) / (eta * length * length)
    n = len(pos)
    result = np.zeros((3 * n, 3 * n))
    for i in range(n):
        for j in range(n):
            d = pos[i] - pos[j]
            phase = np.exp(1j * (q[0] * d[0] + q[1] * d[1] + q[2] * d[2])) * weight
            for a_ in range(3):
                for b in range(3):
                    projector = (1.0 if a_ == b else 0.0) - q[a_] * q[b] / q2
                    result[3 * i + a_, 3 * j + b] = np.sum(phase * projector).real
    return result


def swan_brady(h, a=RADIUS):
    lam = a / h
    return (1 - 9 / 16 * lam + lam ** 3 / 8 - lam ** 5 / 16), (1 - 9 / 8 * lam + lam ** 3 / 2 - lam ** 5 / 8)


def faxen_midplane(half_gap, a=RADIUS):
    lam = a / half_gap
    return 1 - 1.004 * lam + 0.418 * lam ** 3 + 0.21 * lam ** 4 - 0.169 * lam ** 5


def extrapolated(values, lengths):
    """The L -> infinity limit of v(L) = v + c / L^3 from two box sizes."""
    (v1, v2), (l1, l2) = values, lengths
    return (l2 ** 3 * v2 - l1 ** 3 * v1) / (l2 ** 3 - l1 ** 3)
