"""References for ["LongRange","Electrostatics"] (tests/python/test_electrostatics.py imports them).

Two exact sums written here in numpy, independently of the engine's Ewald split and mesh:
  - gaussian_spectral: Gaussian charges of width w > 0, the plain Fourier sum
        U = (2 pi k_e / V) sum_{k != 0} |S(k)|^2 exp(-k^2 w^2) / k^2 - sum_i q_i^2 k_e / (2 sqrt(pi) w),
    S(k) = sum_i q_i exp(i k.r_i), converged to double precision (no split at all);
  - point_ewald: point charges (w = 0), the classic Ewald sum with its real-space images summed out.
And OpenMM's PME (Reference platform, a tight tolerance) for point charges, where it is installed.

Run as a script it prints the tolerance sweep: for each tolerance, the grid the engine chooses and the
measured force and energy errors against the exact sums (STRUCTMD_LIBRARY must name the library;
PYTHONPATH must reach bindings/python).
"""

import math
import sys

import numpy as np

ONE_4PI_EPS0_OPENMM = 138.935456  # kJ mol^-1 nm e^-2, OpenMM's Coulomb constant


def _wave_vectors(box, kmax):
    """Every k = 2 pi m / L with 0 < |k| <= kmax."""
    ms = [np.arange(-int(kmax * L / (2 * math.pi)) - 1, int(kmax * L / (2 * math.pi)) + 2) for L in box]
    mx, my, mz = np.meshgrid(*ms, indexing="ij")
    k = np.stack([mx.ravel() * 2 * math.pi / box[0], my.ravel() * 2 * math.pi / box[1],
                  mz.ravel() * 2 * math.pi / box[2]], axis=1)
    k2 = np.sum(k * k, axis=1)
    keep = (k2 > 0) & (k2 <= kmax * kmax)
    return k[keep], k2[keep]


def _reciprocal(positions, charges, box, width2, k_e):
    """(2 pi k_e / V) sum_k |S|^2 exp(-k^2 width2) / k^2 and its forces, summed until exp(-k^2 width2) < 1e-18."""
    kmax = math.sqrt(41.5 / width2)
    k, k2 = _wave_vectors(box, kmax)
    volume = float(np.prod(box))
    f = np.exp(-k2 * width2) / k2
    energy, forces = 0.0, np.zeros_like(positions)
    for start in range(0, len(k), 20000):
        kk, ff = k[start:start + 20000], f[start:start + 20000]
        phase = positions @ kk.T                      # (N, K)
        cos, sin = np.cos(phase), np.sin(phase)
        s_re, s_im = charges @ cos, charges @ sin     # S(k)
        energy += 2 * math.pi * k_e / volume * np.sum(ff * (s_re ** 2 + s_im ** 2))
        # F_i = (4 pi k_e / V) q_i sum_k f(k) k Im(S* exp(i k.r_i))
        im = sin * s_re[None, :] - cos * s_im[None, :]
        forces += 4 * math.pi * k_e / volume * charges[:, None] * ((im * ff[None, :]) @ kk)
    return energy, forces


def gaussian_spectral(positions, charges, box, width, k_e=1.0):
    """Energy and forces of Gaussian charges of width > 0 in the periodic box."""
    positions, charges, box = np.asarray(positions, float), np.asarray(charges, float), np.asarray(box, float)
    energy, forces = _reciprocal(positions, charges, box, width * width, k_e)
    return energy - k_e * np.sum(charges ** 2) / (2 * math.sqrt(math.pi) * width), forces


def gaussian_spectral_virial(positions, charges, box, width, k_e=1.0):
    """The virial tensor W_ab = -dU/d(strain_ab) of Gaussian charges of width > 0 (w fixed):
    sum_k E_k [delta_ab - 2 (w^2 + 1/k^2) k_a k_b], E_k the energy of wave vector k."""
    positions, charges, box = np.asarray(positions, float), np.asarray(charges, float), np.asarray(box, float)
    k, k2 = _wave_vectors(box, math.sqrt(41.5) / width)
    phase = positions @ k.T
    s2 = (charges @ np.cos(phase)) ** 2 + (charges @ np.sin(phase)) ** 2
    energy = 2 * math.pi * k_e / float(np.prod(box)) * s2 * np.exp(-k2 * width * width) / k2
    weight = 2 * (width * width + 1 / k2) * energy
    return np.sum(energy) * np.eye(3) - (k * weight[:, None]).T @ k


def point_ewald(positions, charges, box, k_e=1.0):
    """Energy and forces of neutral point charges in the periodic box, by the Ewald sum."""
    positions, charges, box = np.asarray(positions, float), np.asarray(charges, float), np.asarray(box, float)
    assert abs(np.sum(charges)) < 1e-12, "point_ewald expects a neutral system"
    alpha = 5.0 / np.min(box)  # erfc(alpha r) < 1e-17 beyond the images summed below
    energy, forces = _reciprocal(positions, charges, box, 1.0 / (4 * alpha * alpha), k_e)
    energy -= k_e * alpha / math.sqrt(math.pi) * np.sum(charges ** 2)
    images = np.array([[a, b, c] for a in range(-2, 3) for b in range(-2, 3) for c in range(-2, 3)], float) * box
    for i in range(len(positions)):
        d = positions[None, :, :] - positions[i] + images[:, None, :]  # r_j + n - r_i
        r = np.linalg.norm(d, axis=2)
        mask = r > 1e-12
        rr = np.where(mask, r, 1.0)
        u = np.where(mask, np.array([math.erfc(x) for x in (alpha * rr).ravel()]).reshape(rr.shape) / rr, 0.0)
        energy += 0.5 * k_e * charges[i] * np.sum(charges[None, :] * u)
        dudr = np.where(mask, -u / rr - 2 * alpha / math.sqrt(math.pi) * np.exp(-(alpha * rr) ** 2) / rr, 0.0)
        forces[i] += k_e * charges[i] * np.sum((charges[None, :] * dudr / rr)[:, :, None] * d, axis=(0, 1))
    return energy, forces


def openmm_pme(positions, charges, box, k_e=1.0, tolerance=1e-7):
    """OpenMM's PME for point charges (lengths read as nm), scaled to the Coulomb constant k_e; None
    where OpenMM is not installed."""
    try:
        import openmm
        import openmm.unit as unit
    except ImportError:
        return None
    system = openmm.System()
    system.setDefaultPeriodicBoxVectors(openmm.Vec3(box[0], 0, 0), openmm.Vec3(0, box[1], 0),
                                        openmm.Vec3(0, 0, box[2]))
    nonbonded = openmm.NonbondedForce()
    nonbonded.setNonbondedMethod(openmm.NonbondedForce.PME)
    nonbonded.setCutoffDistance(0.49 * min(box))
    nonbonded.setEwaldErrorTolerance(tolerance)
    for q in charges:
        system.addParticle(1.0)
        nonbonded.addParticle(float(q), 1.0, 0.0)
    system.addForce(nonbonded)
    context = openmm.Context(system, openmm.VerletIntegrator(0.001), openmm.Platform.getPlatformByName("Reference"))
    context.setPositions([openmm.Vec3(*p) for p in np.asarray(positions, float)])
    state = context.getState(getEnergy=True, getForces=True)
    scale = k_e / ONE_4PI_EPS0_OPENMM
    energy = state.getPotentialEnergy().value_in_unit(unit.kilojoule_per_mole) * scale
    forces = np.array(state.getForces(asNumpy=True).value_in_unit(unit.kilojoule_per_mole / unit.nanometer)) * scale
    return energy, forces


def random_neutral_system(n, box, seed, minimum=0.3):
    """n charges in (-1, 1) summing to zero, each at least `minimum` from the others (minimum image)."""
    rng = np.random.default_rng(seed)
    positions = []
    while len(positions) < n:
        c = rng.uniform(-0.5, 0.5, 3) * box
        if all(np.linalg.norm((c - p) - box * np.round((c - p) / box)) > minimum for p in positions):
            positions.append(c)
    charges = rng.uniform(-1.0, 1.0, n)
    charges -= charges.mean()
    return np.array(positions), charges


def document(positions, charges, box, parameters, units="None"):
    """A UAMMD-structured input of the charges alone with one ["LongRange","Electrostatics"] entry."""
    return {
        "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": "electrostatics"}}},
        "global": {
            "units": {"type": ["Units", units]},
            "types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"],
                      "data": [["A", 1.0, 0.1, 0.0]]},
            "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"],
                         "data": [[[float(b) for b in box], 1.0]]},
        },
        "integrator": {
            "vv": {"type": ["Verlet", "VelocityVerlet"], "parameters": {"timeStep": 0.0001}},
            "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
                         "data": [[1, "vv", 1]]},
        },
        "state": {"labels": ["id", "position", "charge"],
                  "data": [[i, [float(x) for x in p], float(q)] for i, (p, q) in enumerate(zip(positions, charges))]},
        "topology": {"structure": {"labels": ["id", "type"], "data": [[i, "A"] for i in range(len(positions))]},
                     "forceField": {"elec": {"type": ["LongRange", "Electrostatics"], "parameters": parameters}}},
    }


def chosen_split_and_grid(charges, box, width, tolerance, split=0.0):
    """The far width s, the pair term's cutoff (0: none) and the grid the engine chooses (the rules of
    docs/input-format.md, ["LongRange","Electrostatics"]), for printing."""
    lo, hi = 0.0, 30.0  # erfc(x) + 2x exp(-x^2) / sqrt(pi) = tolerance, by bisection
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if math.erfc(mid) + 2 * mid * math.exp(-mid * mid) / math.sqrt(math.pi) > tolerance:
            lo = mid
        else:
            hi = mid
    x = hi
    reach, half = 2 * x, 0.5 * min(box)
    if split > 0:
        s = math.sqrt(width ** 2 + 0.25 / split ** 2)
    else:
        spacing = (float(np.prod(box)) / max(np.count_nonzero(charges), 1)) ** (1 / 3)
        wider = min(0.5 * spacing, 0.999 * half / reach)
        s = wider if wider > 1.5 * width else width
    h = s * 3.0 * tolerance ** (1 / 6)

    def friendly(n):
        while True:
            m = n
            for f in (2, 3, 5):
                while m % f == 0:
                    m //= f
            if m == 1:
                return n
            n += 1
    grid = [friendly(max(int(math.ceil(L / h)), 12)) for L in box]
    return s, (reach * s if s > width else 0.0), grid


def errors(forces, energy, reference):
    """Force error: RMS of the difference over RMS of the reference force; energy: relative."""
    ref_energy, ref_forces = reference
    force_error = math.sqrt(np.mean(np.sum((forces - ref_forces) ** 2, axis=1)) / np.mean(np.sum(ref_forces ** 2, axis=1)))
    return force_error, abs(energy - ref_energy) / abs(ref_energy)


def sweep():
    import structmd
    box = np.array([6.0, 6.5, 7.0])
    positions, charges = random_neutral_system(60, box, seed=3)
    exact = {0.0: point_ewald(positions, charges, box), 0.4: gaussian_spectral(positions, charges, box, 0.4)}
    print("60 charges in a %g x %g x %g box" % tuple(box))
    print("gaussianWidth tolerance  force-error  energy-error  far-width  cutoff  grid")
    for width, reference in exact.items():
        for tolerance in (1e-2, 1e-3, 1e-4, 1e-5, 1e-6):
            doc = document(positions, charges, box, {"dielectricConstant": 1.0, "gaussianWidth": width,
                                                     "tolerance": tolerance})
            with structmd.Simulation({"backend": "cpu", "precision": "double", "log": "quiet"}) as sim:
                sim.load(doc)
                force_error, energy_error = errors(sim.forces, sim.energy("elec"), reference)
            s, cutoff, grid = chosen_split_and_grid(charges, box, width, tolerance)
            print(f"{width:13.2f} {tolerance:9.0e}  {force_error:11.2e}  {energy_error:12.2e}  {s:9.3f}  {cutoff:6.3f}  "
                  + "x".join(map(str, grid)))
    mm = openmm_pme(positions, charges, box)
    if mm is not None:
        print("OpenMM PME against the Ewald sum: force %.2e, energy %.2e" % errors(mm[1], mm[0], exact[0.0]))


if __name__ == "__main__":
    sys.exit(sweep())
