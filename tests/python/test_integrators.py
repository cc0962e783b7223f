"""The integrators of docs/input-format.md ("integrator"): Langevin BBK and GJF, Brownian
Euler-Maruyama, steepest descent, their schedule, their group and their reproducibility.

A statistical check compares a sample mean with its exact expectation and allows five standard
errors of that mean. The standard error follows from the number of samples and their
autocorrelation, known in closed form for the linear systems used (free particles, harmonic
traps), so a correct integrator fails a check with probability below 1e-6, while a wrong noise
amplitude (a factor sqrt(2)), mass or friction misses by tens of standard errors. Every run has a
fixed seed, so the outcome is repeatable.

Moments of a unit Gaussian u whose values k samples apart have correlation r(k) (Isserlis):
u^2 has mean 1, variance 2 and autocorrelation r^2; u^4 has mean 3, variance 96 and autocorrelation
(3 r^2 + r^4) / 4.
"""

import math
import re

import numpy as np
import pytest

import structmd

KT = 1.2  # the ensemble's temperature; units None, so k_B = 1 and this is k_B T
TYPES = [["light", 1.0, 0.5, 0.0], ["heavy", 3.0, 1.0, 0.0]]  # name, mass, radius, charge
MASS = {row[0]: row[1] for row in TYPES}
RADIUS = {row[0]: row[2] for row in TYPES}
BOLTZMANN_KCAL_MOL = 1.987191e-3  # k_B of ["Units","KcalMol_A"], kcal/(mol K)
TOLERANCE_IN_ERRORS = 5.0


# ---- input documents ------------------------------------------------------------------------------

def document(positions, types, integrators, schedule, force_field=None, box=20.0, velocities=None, seed=1,
             fundamental=None, units=None):
    """integrators: {name: entry}; schedule: [(name, steps), ...] in order."""
    labels = ["id", "position"] + (["velocity"] if velocities is not None else [])
    rows = []
    for i, position in enumerate(positions):
        row = [i, [float(c) for c in position]]
        if velocities is not None:
            row.append([float(c) for c in velocities[i]])
        rows.append(row)
    doc = {
        "system": {"info": {"type": ["Simulation", "Information"],
                            "parameters": {"name": "integrators", "seed": seed}}},
        "global": {
            "types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"], "data": TYPES},
            "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"],
                         "data": [[[box, box, box], KT]]},
        },
        "integrator": dict(integrators, schedule={
            "type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
            "data": [[k + 1, name, steps] for k, (name, steps) in enumerate(schedule)]}),
        "state": {"labels": labels, "data": rows},
        "topology": {"structure": {"labels": ["id", "type"], "data": [[i, t] for i, t in enumerate(types)]},
                     "forceField": force_field or {}},
    }
    if fundamental:
        doc["global"]["fundamental"] = {"type": ["Fundamental", "Time"], "parameters": fundamental}
    if units:
        doc["global"]["units"] = {"type": ["Units", units]}
    return doc


def langevin(kind, time_step, friction, **extra):
    return {"type": ["Langevin", kind],
            "parameters": {"timeStep": time_step, "frictionConstant": friction, **extra}}


def brownian(time_step, viscosity, **extra):
    return {"type": ["Brownian", "EulerMaruyama"],
            "parameters": {"timeStep": time_step, "viscosity": viscosity, **extra}}


def steepest_descent(h, max_force, cls="SteepestDescent", **extra):
    return {"type": [cls, "SteepestDescent"], "parameters": {"h": h, "maxObjectiveForce": max_force, **extra}}


def verlet(time_step, **extra):
    return {"type": ["Verlet", "VelocityVerlet"], "parameters": {"timeStep": time_step, **extra}}


def trap(stiffness, centres):
    """Each particle i tied to centres[i] by U = 1/2 K_i |r_i - c_i|^2."""
    return {"type": ["Bond1", "FixedHarmonic"], "labels": ["id_i", "K", "r0", "position"],
            "data": [[i, float(k), 0.0, [float(c) for c in centre]]
                     for i, (k, centre) in enumerate(zip(stiffness, centres))]}


def lennard_jones():
    return {"nl": {"type": ["VerletConditionalListSet", "all"], "parameters": {"cutOffVerletFactor": 1.2}},
            "lj": {"type": ["NonBonded", "LennardJonesType1"], "parameters": {"cutOffFactor": 2.5, "condition": "all"},
                   "labels": ["name_i", "name_j", "epsilon", "sigma"],
                   "data": [["light", "light", 1.0, 1.0], ["light", "heavy", 1.0, 1.0], ["heavy", "heavy", 1.0, 1.0]]}}


def half_light_half_heavy(n):
    return ["light"] * (n // 2) + ["heavy"] * (n - n // 2)


def perturbed_lattice(cells, spacing, jitter, seed):
    """cells^3 particles on a cubic lattice filling a periodic box of edge cells * spacing, each moved
    by up to `jitter` along each axis."""
    grid = np.array([[i, j, k] for i in range(cells) for j in range(cells) for k in range(cells)], dtype=float)
    lattice = (grid + 0.5) * spacing - 0.5 * cells * spacing
    return lattice + np.random.default_rng(seed).uniform(-jitter, jitter, lattice.shape), cells * spacing


def minimum_image(d, box):
    return d - box * np.round(d / box)


# ---- statistics -----------------------------------------------------------------------------------

def standard_error(variance, correlation, samples, chains):
    """Standard error of the mean over `chains` independent stationary series of `samples` values,
    each of the given variance, values k apart correlated by correlation(k)."""
    lags = np.arange(1, samples)
    inflation = 1.0 + 2.0 * np.sum((1.0 - lags / samples) * correlation(lags))
    return math.sqrt(variance * inflation / (samples * chains))


def gaussian_moments(u, correlation):
    """<u^2> and <u^4> of u (samples x chains), each with its five-standard-error tolerance, for u that
    should be N(0, 1) with correlation(k) between values k samples apart."""
    samples, chains = u.shape
    second_error = standard_error(2.0, lambda k: correlation(k) ** 2, samples, chains)
    fourth_error = standard_error(96.0, lambda k: (3.0 * correlation(k) ** 2 + correlation(k) ** 4) / 4.0,
                                  samples, chains)
    return ((float(np.mean(u ** 2)), TOLERANCE_IN_ERRORS * second_error),
            (float(np.mean(u ** 4)), TOLERANCE_IN_ERRORS * fourth_error))


def assert_unit_gaussian(u, correlation, what, variance=1.0):
    """u should be N(0, variance): checks <u^2> = variance and <u^4> = 3 variance^2."""
    (second, second_tol), (fourth, fourth_tol) = gaussian_moments(u / math.sqrt(variance), correlation)
    assert abs(second - 1.0) < second_tol, f"{what}: <u^2>/expected = {second:.5f}, allowed 1 +- {second_tol:.5f}"
    assert abs(fourth - 3.0) < fourth_tol, f"{what}: <u^4>/expected = {fourth:.5f}, allowed 3 +- {fourth_tol:.5f}"
    return second, fourth


def oscillator_correlations(omega, friction):
    """Autocorrelations of position and velocity of the underdamped Langevin oscillator (friction < 2
    omega), as functions of the time lag: exp(-gamma t/2) (cos w1 t +- gamma/(2 w1) sin w1 t)."""
    w1 = math.sqrt(omega ** 2 - friction ** 2 / 4.0)
    kappa = friction / (2.0 * w1)
    envelope = lambda t: np.exp(-0.5 * friction * t)
    position = lambda t: envelope(t) * (np.cos(w1 * t) + kappa * np.sin(w1 * t))
    velocity = lambda t: envelope(t) * (np.cos(w1 * t) - kappa * np.sin(w1 * t))
    return position, velocity


# ---- Langevin ------------------------------------------------------------------------------------

def langevin_trajectory(options, kind, n, time_step, friction, omega, burn_in, samples, every, kt=KT,
                        units=None, temperature=None):
    """n non-interacting particles, half light and half heavy, free (omega None) or each in a harmonic
    trap K_i = m_i omega^2 (so every particle has the frequency omega). Positions start at equilibrium
    (drawn here), velocities are redrawn by the integrator. Returns the velocity and position
    components scaled to unit variance at temperature kt, each (samples, 3 n)."""
    types = half_light_half_heavy(n)
    mass = np.array([MASS[t] for t in types])
    rng = np.random.default_rng(7)
    if omega is None:
        positions = rng.uniform(-10.0, 10.0, (n, 3))
        force_field = {}
    else:
        stiffness = mass * omega ** 2
        positions = rng.normal(size=(n, 3)) * np.sqrt(kt / stiffness)[:, None]
        force_field = {"trap": trap(stiffness, np.zeros((n, 3)))}
    extra = {} if temperature is None else {"temperature": temperature}
    doc = document(positions, types, {"langevin": langevin(kind, time_step, friction, **extra)},
                   [("langevin", burn_in + samples * every)], force_field=force_field, units=units)
    velocity, position = [], []
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        sim.step(burn_in)
        for _ in range(samples):
            sim.step(every)
            velocity.append((sim.velocities * np.sqrt(mass / kt)[:, None]).ravel())
            if omega is not None:
                position.append((sim.positions * np.sqrt(stiffness / kt)[:, None]).ravel())
    return np.array(velocity), (np.array(position) if omega is not None else None)


@pytest.mark.parametrize("kind", ["BBK", "GJF"])
@pytest.mark.parametrize("trapped", [False, True], ids=["free", "trap"])
def test_langevin_samples_maxwell_boltzmann(options, kind, trapped):
    # 3000 particles x 3 components = 9000 independent chains, 200 samples 10 steps (0.1/gamma) apart.
    # Free particles: both schemes make the velocity an AR(1) series v' = c v + noise with
    # c = (1 - gamma dt/2)/(1 + gamma dt/2), stationary variance kT/m exactly, so samples k apart
    # correlate by c^(10 k); the standard error of <m v^2/kT> is then 0.0033 (5 errors: 1.7%).
    # The free case runs at the integrator's own temperature, 1.5, instead of the ensemble's.
    # Trap (omega = gamma = 1): the correlations are the continuous oscillator's (time step 0.01, the
    # difference is O(dt)); the schemes' own biases, O((omega dt)^2/4) = 2.5e-5, are far below the
    # tolerances (about 1% for <v^2>, 2% for <K x^2>).
    time_step, friction, every = 0.01, 1.0, 10
    omega = 1.0 if trapped else None
    kt = KT if trapped else 1.5
    velocity, position = langevin_trajectory(options, kind, 3000, time_step, friction, omega, burn_in=100,
                                             samples=200, every=every, kt=kt,
                                             temperature=None if trapped else kt)
    if trapped:
        position_correlation, velocity_correlation = oscillator_correlations(omega, friction)
        lag_time = every * time_step
        assert_unit_gaussian(velocity, lambda k: velocity_correlation(k * lag_time), f"{kind} trap velocities")
        assert_unit_gaussian(position, lambda k: position_correlation(k * lag_time), f"{kind} trap positions")
    else:
        c = (1.0 - 0.5 * friction * time_step) / (1.0 + 0.5 * friction * time_step)
        assert_unit_gaussian(velocity, lambda k: c ** (every * k), f"{kind} free velocities")


def test_langevin_temperature_is_in_the_units_of_the_document(options):
    # ["Units","KcalMol_A"]: the thermal energy is k_B T with k_B in kcal/(mol K). 9000 chains,
    # 40 samples 10 steps (0.1/gamma) apart; as in the free case above, 5 standard errors of
    # <m v^2/kT> are 3.7%, while forgetting k_B is off by a factor 500.
    kt = BOLTZMANN_KCAL_MOL * 300.0
    velocity, _ = langevin_trajectory(options, "BBK", 3000, 0.01, 1.0, None, burn_in=0, samples=40, every=10,
                                      kt=kt, units="KcalMol_A", temperature=300.0)
    c = (1.0 - 0.005) / (1.0 + 0.005)
    assert_unit_gaussian(velocity, lambda k: c ** (10 * k), "BBK velocities in kcal/mol units")


def test_gjf_samples_the_configuration_exactly_at_a_large_time_step_where_bbk_does_not(options):
    # A trap of frequency omega = 1 at dt = 1 (half the stability limit 2/omega), gamma = 1. Known
    # results for these two schemes (Gronbech-Jensen & Farago, Mol. Phys. 111, 983 (2013); checked by
    # solving the stationary covariance of both linear recursions): GJF gives <K x^2> = kT at any
    # stable dt and on-site velocities <m v^2> = kT (1 - q), q = (omega dt)^2/4; BBK gives
    # <K x^2> = <m v(n+1/2)^2> = kT / (1 - q). Here q = 1/4: GJF 1 and 3/4, BBK 4/3 and 4/3.
    # Samples are 20 steps apart: the deterministic map has eigenvalues of modulus sqrt(a) = 0.58
    # (a = (1 - gamma dt/2)/(1 + gamma dt/2) = 1/3 is its determinant), so such samples are
    # correlated by about 0.58^20 = 2e-5 and count as independent: 7500 chains x 20 samples give a
    # standard error of sqrt(2/150000) = 0.4% (5 errors: 1.8%).
    q = 0.25
    expected = {"GJF": (1.0, 1.0 - q), "BBK": (1.0 / (1.0 - q), 1.0 / (1.0 - q))}
    independent = lambda k: np.zeros_like(k, dtype=float)
    configurational = {}
    for kind, (position_variance, velocity_variance) in expected.items():
        velocity, position = langevin_trajectory(options, kind, 2500, 1.0, 1.0, 1.0, burn_in=100, samples=20,
                                                 every=20)
        assert_unit_gaussian(position, independent, f"{kind} K x^2 / kT", position_variance)
        assert_unit_gaussian(velocity, independent, f"{kind} m v^2 / kT", velocity_variance)
        configurational[kind] = float(np.mean(position ** 2))
    # BBK's configurational error, a third, is many tolerances (1.8%) larger than GJF's.
    assert abs(configurational["BBK"] - 1.0) > 10 * abs(configurational["GJF"] - 1.0) + 0.2, configurational


# ---- Brownian ------------------------------------------------------------------------------------

def unwrapped_trajectory(sim, reads, every, box):
    """Positions read every `every` steps, unwrapped on the host: between two reads a particle moves
    much less than half the box, so the minimum image of the change is its displacement."""
    wrapped = sim.positions
    unwrapped = [wrapped.copy()]
    for _ in range(reads):
        sim.step(every)
        now = sim.positions
        assert np.all((now >= -box / 2) & (now < box / 2)), "positions must stay wrapped in [-L/2, L/2)"
        unwrapped.append(unwrapped[-1] + minimum_image(now - wrapped, box))
        wrapped = now
    return np.array(unwrapped)


def test_brownian_free_diffusion_has_the_stokes_einstein_coefficient(options):
    # D_i = kT / (6 pi eta a_i) for the radii 0.5 and 1; over a window t the displacement along each
    # axis is N(0, 2 D_i t) exactly for Euler-Maruyama (a sum of independent Gaussian steps), and
    # successive windows are independent. 4000 particles x 3 axes x 10 windows of t = 1 give
    # 120000 independent values: 5 standard errors of <dx^2/(2 D t)> are 5 sqrt(2/120000) = 2.0%,
    # of <dx^4>/(2 D t)^2 = 3: 5 sqrt(96/120000) = 14% (4.7% of 3). A missing factor 2 or sqrt(2)
    # in the noise is 29% to 100% off. The box (8) is small, so most particles cross it.
    n, box, viscosity, time_step, every, window, windows = 4000, 8.0, 0.5, 0.01, 10, 100, 10
    types = half_light_half_heavy(n)
    radius = np.array([RADIUS[t] for t in types])
    diffusion = KT / (6.0 * math.pi * viscosity * radius)
    positions = np.random.default_rng(3).uniform(-box / 2, box / 2, (n, 3))
    velocities = np.ones((n, 3))
    doc = document(positions, types, {"bd": brownian(time_step, viscosity)}, [("bd", window * windows)], box=box,
                   velocities=velocities)
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        trajectory = unwrapped_trajectory(sim, window * windows // every, every, box)
        assert sim.time == pytest.approx(window * windows * time_step, rel=1e-12)
        # Overdamped particles have no velocity: the integrator zeroes it.
        assert np.all(sim.velocities == 0.0) and sim.energy("kinetic") == 0.0
    assert np.count_nonzero(np.any(np.abs(trajectory[-1]) > box / 2, axis=1)) > n // 10, "too few crossed the box"
    ends = trajectory[::window // every]
    displacement = (ends[1:] - ends[:-1]) / np.sqrt(2.0 * diffusion * window * time_step)[:, None]
    assert_unit_gaussian(displacement.reshape(windows, 3 * n), lambda k: np.zeros_like(k, dtype=float),
                         "Brownian displacements / sqrt(2 D t)")


def test_brownian_particles_in_a_trap_sample_the_boltzmann_distribution(options):
    # Mobility M_i = 1/(6 pi eta a_i); trap K_i = 1/(100 M_i dt), so r = 1 - M K dt = 0.99 for every
    # particle. Euler-Maruyama then makes each coordinate an AR(1) series x' = r x + noise of variance
    # 2 kT M dt, whose stationary variance is kT/K / (1 - M K dt/2) (a 0.5% excess, compared exactly).
    # 4000 particles x 3 axes, 125 samples 10 steps apart, correlated by r^(10 k): 5 standard errors
    # of <K x^2> are 1.8%.
    n, viscosity, time_step, every, samples = 4000, 1.0, 0.01, 10, 125
    types = half_light_half_heavy(n)
    mobility = 1.0 / (6.0 * math.pi * viscosity * np.array([RADIUS[t] for t in types]))
    stiffness = 1.0 / (100.0 * mobility * time_step)
    r = 1.0 - 0.01
    positions = np.random.default_rng(5).normal(size=(n, 3)) * np.sqrt(KT / stiffness)[:, None]
    doc = document(positions, types, {"bd": brownian(time_step, viscosity)}, [("bd", 500 + every * samples)],
                   force_field={"trap": trap(stiffness, np.zeros((n, 3)))})
    scaled = []
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        sim.step(500)
        for _ in range(samples):
            sim.step(every)
            scaled.append((sim.positions * np.sqrt(stiffness / KT)[:, None]).ravel())
    assert_unit_gaussian(np.array(scaled), lambda k: r ** (every * k), "Brownian <K x^2>/kT",
                         variance=1.0 / (1.0 - 0.01 / 2.0))


# ---- steepest descent ----------------------------------------------------------------------------

def overlapping_lennard_jones(h, max_force, steps, cls="SteepestDescent", fundamental=None):
    """216 LJ particles filling a periodic box at density 0.75, jittered so that many pairs overlap."""
    positions, box = perturbed_lattice(6, 1.1, 0.2, seed=3)
    types = ["light"] * len(positions)
    return document(positions, types, {"minimise": steepest_descent(h, max_force, cls)}, [("minimise", steps)],
                    force_field=lennard_jones(), box=box, fundamental=fundamental)


def test_steepest_descent_follows_its_update_rule_and_lowers_the_energy(options):
    # Each step moves x += (h / max|F|) F and keeps the move only if the energy drops; h grows by
    # 1.001 after a kept move and shrinks by 0.999 after an undone one. Recomputed here from the
    # forces read before each step, to rounding.
    h0, steps = 0.01, 100
    doc = overlapping_lennard_jones(h0, 1e-3, steps, fundamental={"currentStep": 7, "simulationTime": 2.5})
    h = h0
    kept = 0
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        box = sim.box
        energy = sim.energy()
        for k in range(steps):
            forces, before = sim.forces, sim.positions
            sim.step(1)
            after, new_energy = sim.positions, sim.energy()
            assert sim.step_number == 7 + k + 1 and sim.time == 2.5, "minimisation advances the step, not the time"
            moved = minimum_image(after - before, box)
            if np.any(moved != 0.0):
                expected = h / np.max(np.linalg.norm(forces, axis=1)) * forces
                np.testing.assert_allclose(moved, expected, rtol=1e-9, atol=1e-12 * h)
                assert new_energy < energy, f"step {k}: a kept move must lower the energy"
                h *= 1.001
                kept += 1
            else:
                assert new_energy == energy, f"step {k}: an undone move must leave the energy as it was"
                h *= 0.999
            energy = new_energy
    assert kept > 10 and energy < 0.0, "the overlaps must have been relaxed"


def test_steepest_descent_stops_once_the_largest_force_is_below_the_objective(options):
    max_force = 5.0
    with structmd.Simulation(options) as sim:
        sim.load(overlapping_lennard_jones(0.01, max_force, 400))
        initial_energy = sim.energy()
        for k in range(400):
            largest = np.max(np.linalg.norm(sim.forces, axis=1))
            before = sim.positions
            sim.step(1)
            if largest < max_force:
                break
        assert largest < max_force, "400 steps should reach max|F| < 5 from this start"
        assert np.array_equal(sim.positions, before), "a converged minimiser must not move"
        converged, energy = sim.positions, sim.energy()
        sim.step(20)
        assert np.array_equal(sim.positions, converged) and sim.energy() == energy
        assert energy < initial_energy
        assert sim.time == 0.0 and sim.step_number == k + 21


def test_the_three_spellings_of_steepest_descent_are_one_integrator(options):
    trajectories = []
    for cls in ("SteepestDescent", "Minimization", "Mininimization"):
        with structmd.Simulation(options) as sim:
            sim.load(overlapping_lennard_jones(0.01, 1e-3, 30, cls=cls))
            sim.run()
            trajectories.append(sim.positions)
    assert np.array_equal(trajectories[0], trajectories[1]) and np.array_equal(trajectories[0], trajectories[2])


def test_steepest_descent_needs_no_time_step(options):
    doc = overlapping_lennard_jones(0.01, 1.0, 5)
    assert "fundamental" not in doc["global"] and "timeStep" not in doc["integrator"]["minimise"]["parameters"]
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        sim.run()
        assert sim.step_number == 5 and sim.time == 0.0


def test_steepest_descent_prints_its_progress_every_n_steps_print_progress(options, tmp_path):
    doc = overlapping_lennard_jones(0.01, 1e-3, 10)
    doc["integrator"]["minimise"]["parameters"]["nStepsPrintProgress"] = 4
    log = tmp_path / "structmd.log"
    largest = {}
    with structmd.Simulation({**options, "log": "info", "log_file": str(log)}) as sim:
        sim.load(doc)
        for step in range(10):
            largest[step] = np.max(np.linalg.norm(sim.forces, axis=1))
            sim.step(1)
    pattern = re.compile(r"steepest descent minimise, step (\d+): max\|F\| ([\d.e+-]+) \(objective ([\d.e+-]+)\), h ")
    found = [pattern.search(line) for line in log.read_text().splitlines()]
    found = [match for match in found if match]
    assert [int(match[1]) for match in found] == [0, 4, 8]
    for match in found:
        assert float(match[2]) == pytest.approx(largest[int(match[1])], rel=1e-5)
        assert float(match[3]) == pytest.approx(1e-3)


# ---- schedule ------------------------------------------------------------------------------------

# |F| <= K |displacement| <= 10 x 0.5 sqrt(3) = 8.7 in the traps below (the minimiser only lowers it),
# so a force term dt |F|/m of BBK's first step is at most 0.087.
FORCE_TERM = 0.01 * 10.0 * 0.5 * math.sqrt(3.0)


def relax_then_thermostat(reset=True):
    """200 particles displaced from their trap centres, all moving at +5 along x: 30 steps of steepest
    descent, then 20 of BBK at dt = 0.01, from step 100 and time 2.5."""
    n = 200
    rng = np.random.default_rng(11)
    centres = rng.uniform(-8.0, 8.0, (n, 3))
    positions = centres + rng.uniform(-0.5, 0.5, (n, 3))
    velocities = np.tile([5.0, 0.0, 0.0], (n, 1))
    integrators = {"relax": steepest_descent(0.02, 0.5),
                   "thermostat": langevin("BBK", 0.01, 1.0, resetVelocities=reset)}
    return document(positions, half_light_half_heavy(n), integrators,
                    [("relax", 30), ("thermostat", 20)],
                    force_field={"trap": trap(np.full(n, 10.0), centres)}, velocities=velocities,
                    fundamental={"currentStep": 100, "simulationTime": 2.5})


def test_a_schedule_of_two_integrators_counts_steps_and_time_and_resets_velocities_once(options):
    # After the reset, the mean over the 200 particles of v_x(1/2) is that of the redrawn N(0, kT/m)
    # components, standard error sqrt(kT <1/m> / 200) = 0.063 (the step's own noise adds 0.011),
    # plus force terms of at most dt |F|/m <= FORCE_TERM: 5 errors and that bound make 0.41, against
    # 5 (1 - gamma dt/2)/(1 + gamma dt/2) = 4.95 without the reset.
    n = 200
    mass = np.array([MASS[t] for t in half_light_half_heavy(n)])
    variance_of_mean = (KT + 2.0 * KT * 0.01) * np.mean(1.0 / mass) / n
    allowed = TOLERANCE_IN_ERRORS * math.sqrt(variance_of_mean) + FORCE_TERM
    with structmd.Simulation(options) as sim:
        sim.load(relax_then_thermostat())
        energy = sim.energy()
        sim.step(30)
        assert sim.step_number == 130 and sim.time == 2.5
        assert sim.energy() < energy, "the minimiser ran"
        assert np.all(sim.velocities == [5.0, 0.0, 0.0]), "the minimiser leaves velocities alone"
        sim.step(1)
        assert sim.step_number == 131 and sim.time == pytest.approx(2.51, rel=1e-12)
        assert abs(np.mean(sim.velocities[:, 0])) < allowed, "the thermostat's stage begins with a velocity reset"
        sim.velocities = np.tile([5.0, 0.0, 0.0], (n, 1))
        sim.step(1)
        assert np.mean(sim.velocities[:, 0]) > 4.95 - allowed, "the reset happens once, when the stage begins"
        sim.step(18)
        assert sim.step_number == 150 and sim.time == pytest.approx(2.5 + 20 * 0.01, rel=1e-12)
        sim.velocities = np.tile([5.0, 0.0, 0.0], (n, 1))
        sim.step(1)  # past the schedule's end: the thermostat goes on, without a second reset
        assert sim.step_number == 151 and sim.time == pytest.approx(2.5 + 21 * 0.01, rel=1e-12)
        assert np.mean(sim.velocities[:, 0]) > 4.95 - allowed, "no stage begins past the end"


def test_a_stage_begins_the_same_whether_its_first_step_opens_a_call_or_not(options):
    with structmd.Simulation(options) as in_chunks, structmd.Simulation(options) as at_once:
        in_chunks.load(relax_then_thermostat())
        for chunk in (30, 1, 19):
            in_chunks.step(chunk)
        at_once.load(relax_then_thermostat())
        at_once.run()
        assert at_once.step_number == 150 and at_once.time == in_chunks.time
        assert np.array_equal(at_once.positions, in_chunks.positions)
        assert np.array_equal(at_once.velocities, in_chunks.velocities)


def test_without_reset_langevin_keeps_the_velocities_it_is_given(options):
    with structmd.Simulation(options) as sim:
        sim.load(relax_then_thermostat(reset=False))
        sim.step(31)
        # v(1/2) = [(1 - g) v(-1/2) + dt (F + R)/m]/(1 + g) with v(-1/2) = 5 - dt/2 F/m: on average
        # 5 (1 - g)/(1 + g) = 4.95, the noise's mean having a standard error sqrt(2 kT gamma dt <1/m> / 200)
        # = 0.011, the force terms adding at most FORCE_TERM.
        n = 200
        mass = np.array([MASS[t] for t in half_light_half_heavy(n)])
        allowed = TOLERANCE_IN_ERRORS * math.sqrt(2.0 * KT * 0.01 * np.mean(1.0 / mass) / n) + FORCE_TERM
        assert np.mean(sim.velocities[:, 0]) == pytest.approx(5.0 * 0.995 / 1.005, abs=allowed)


# ---- groups --------------------------------------------------------------------------------------

GROUP_CASES = {
    "VelocityVerlet": verlet(0.002),
    "BBK": langevin("BBK", 0.002, 1.0),
    "GJF": langevin("GJF", 0.002, 1.0),
    "EulerMaruyama": brownian(0.002, 1.0),
    "SteepestDescent": steepest_descent(0.01, 1e-3),
}


@pytest.mark.parametrize("kind", GROUP_CASES)
def test_an_integrator_restricted_to_a_group_moves_only_its_particles(options, kind):
    positions, box = perturbed_lattice(4, 1.6, 0.25, seed=9)
    n = len(positions)
    mobile = list(range(0, n, 2))
    velocities = np.random.default_rng(2).normal(size=(n, 3))
    entry = dict(GROUP_CASES[kind])
    entry["parameters"] = dict(entry["parameters"], group="mobile")
    force_field = lennard_jones()
    force_field["groups"] = {"type": ["Groups", "GroupsList"], "labels": ["name", "type", "selection"],
                             "data": [["mobile", "Ids", mobile]]}
    doc = document(positions, half_light_half_heavy(n), {"integrate": entry}, [("integrate", 20)],
                   force_field=force_field, box=box, velocities=velocities)
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        start_positions, start_velocities = sim.positions, sim.velocities
        assert np.all(np.linalg.norm(sim.forces, axis=1) > 1e-3), "every particle must feel a force"
        sim.run()
        still = np.setdiff1d(np.arange(n), mobile)
        assert np.array_equal(sim.positions[still], start_positions[still])
        assert np.array_equal(sim.velocities[still], start_velocities[still])
        assert np.all(np.any(sim.positions[mobile] != start_positions[mobile], axis=1)), "the group must move"


FIXED_CASES = {
    "VelocityVerlet": verlet(0.002),
    "BBK": langevin("BBK", 0.002, 1.0),
    "BBK stopTransRotSteps": langevin("BBK", 0.002, 1.0, stopTransRotSteps=5),
    "GJF": langevin("GJF", 0.002, 1.0),
}


@pytest.mark.parametrize("kind", FIXED_CASES)
def test_inertial_integrators_hold_a_particle_of_mass_zero_fixed_while_its_forces_act(options, tmp_path, kind):
    """Every third particle has mass 0: it keeps its position and zero velocity (its velocity is not
    drawn either), the others feel it and move, and the temperature counts 3 degrees of freedom per
    particle of mass > 0 only."""
    positions, box = perturbed_lattice(4, 1.6, 0.25, seed=4)
    n = len(positions)
    types = ["anchor" if i % 3 == 0 else "light" for i in range(n)]
    anchors = [i for i in range(n) if types[i] == "anchor"]
    free = [i for i in range(n) if types[i] != "anchor"]
    force_field = lennard_jones()
    force_field["lj"]["data"] += [["anchor", "anchor", 1.0, 1.0], ["anchor", "light", 1.0, 1.0],
                                  ["anchor", "heavy", 1.0, 1.0]]
    doc = document(positions, types, {"integrate": FIXED_CASES[kind]}, [("integrate", 40)],
                   force_field=force_field, box=box)
    doc["global"]["types"]["data"] = TYPES + [["anchor", 0.0, 0.5, 0.0]]
    doc["simulationStep"] = {"thermo": {"type": ["ThermodynamicMeasure", "ThermodynamicQuantityMeasure"],
                                        "parameters": {"intervalStep": 10,
                                                       "outputFilePath": str(tmp_path / "thermo.dat")}}}
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        start = sim.positions
        assert np.all(sim.velocities[anchors] == 0.0)
        assert np.all(np.linalg.norm(sim.forces[anchors], axis=1) > 1e-3), "the anchors must feel forces"
        sim.run()
        assert np.array_equal(sim.positions[anchors], start[anchors])
        assert np.all(sim.velocities[anchors] == 0.0)
        assert np.all(np.isfinite(sim.velocities))
        assert np.all(np.any(sim.positions[free] != start[free], axis=1)), "the others must move"
    lines = (tmp_path / "thermo.dat").read_text().splitlines()
    header = lines[0].lstrip("#").split()
    rows = np.array([[float(x) for x in line.split()] for line in lines if not line.startswith("#")])
    kinetic, temperature = rows[:, header.index("kinetic")], rows[:, header.index("temperature")]
    assert np.all(kinetic > 0.0)
    np.testing.assert_allclose(temperature, 2.0 * kinetic / (3.0 * len(free)), rtol=1e-8)


# ---- the drift's bookkeeping ---------------------------------------------------------------------

BOOKKEEPING_CASES = {
    "VelocityVerlet": verlet(0.005),
    "BBK": langevin("BBK", 0.005, 1.0),
    "GJF": langevin("GJF", 0.005, 1.0),
    "EulerMaruyama": brownian(0.002, 0.5),
}


@pytest.mark.parametrize("kind", BOOKKEEPING_CASES)
def test_the_forces_after_each_call_are_those_of_a_fresh_evaluation_of_its_positions(options, kind):
    """The drift kernels of these integrators clear the forces and keep the neighbour list's copy of
    the positions for the evaluation that follows (state/drift_bookkeeping.hpp). Half the particles
    are outside the integrator's group, the host changes the external forces between calls and the
    lists are rebuilt on the way: after every call, and after every change of the external forces,
    the forces must equal those of a new handle loaded at the same positions with the same external
    forces. A force not cleared, an external force counted twice or stale (a drift kernel cleared the
    forces to the old ones), or a particle the list still sees where it was would break the equality."""
    positions, box = perturbed_lattice(7, 1.2, 0.1, seed=4)
    n = len(positions)
    force_field = lennard_jones()
    force_field["groups"] = {"type": ["Groups", "GroupsList"], "labels": ["name", "type", "selection"],
                             "data": [["mobile", "Ids", list(range(0, n, 2))]]}
    entry = dict(BOOKKEEPING_CASES[kind])
    entry["parameters"] = dict(entry["parameters"], group="mobile")
    doc = document(positions, half_light_half_heavy(n), {"integrate": entry}, [("integrate", 1000)],
                   force_field=force_field, box=box, velocities=np.random.default_rng(3).normal(size=(n, 3)))
    rng = np.random.default_rng(5)
    with structmd.Simulation(options) as sim, structmd.Simulation(options) as fresh:
        sim.load(doc)
        fresh.load(doc)
        start = sim.positions
        def assert_fresh_forces(external):
            fresh.positions = sim.positions
            fresh.external_forces = external
            np.testing.assert_allclose(sim.forces, fresh.forces, rtol=0, atol=1e-9 * np.max(np.abs(fresh.forces)))

        for call in range(6):
            external = rng.normal(scale=0.5, size=(n, 3)) if call % 3 != 2 else None
            sim.external_forces = external
            assert_fresh_forces(external)  # what the next step starts from
            sim.step(40)
            assert_fresh_forces(external)
        moved = np.linalg.norm(minimum_image(sim.positions - start, box), axis=1)
        assert np.max(moved) > 0.25, "some particle must move past half the skin, so the lists are rebuilt"
        assert sim.counters["neighbour_list_builds"] > 1


@pytest.mark.parametrize("group", [None, "half"])
def test_the_first_term_stores_the_forces_only_where_it_writes_every_particle(options, group):
    """Where the first term of an evaluation writes every particle's force once (a pair term of no
    group), it stores them instead of adding to a buffer the drift cleared (ForceOutputs::storeForce);
    the terms after it add. A pair term of a group leaves the particles outside it to the clearing.
    After calls of velocity Verlet the forces must be those of a fresh handle at the same positions,
    and the constant force over them (a later term applied twice, stored over the pair forces, or
    added to a stale force outside the group would break one or the other)."""
    positions, box = perturbed_lattice(7, 1.2, 0.1, seed=4)
    n = len(positions)
    gravity = np.array([0.0, 0.3, -0.7])
    def field(with_gravity):
        force_field = lennard_jones()
        if group:
            force_field["groups"] = {"type": ["Groups", "GroupsList"], "labels": ["name", "type", "selection"],
                                     "data": [[group, "Ids", list(range(0, n, 2))]]}
            force_field["lj"]["parameters"] = dict(force_field["lj"]["parameters"], group=group)
        if with_gravity:
            force_field["gravity"] = {"type": ["External", "ConstantForce"],
                                      "parameters": {"constantForce": gravity.tolist()}}
        return force_field
    def doc(with_gravity):
        return document(positions, half_light_half_heavy(n), {"integrate": verlet(0.005)}, [("integrate", 1000)],
                        force_field=field(with_gravity), box=box,
                        velocities=np.random.default_rng(3).normal(size=(n, 3)))
    with structmd.Simulation(options) as sim, structmd.Simulation(options) as fresh, \
            structmd.Simulation(options) as pairs_alone:
        sim.load(doc(True))
        fresh.load(doc(True))
        pairs_alone.load(doc(False))
        for _ in range(4):
            sim.step(25)
            fresh.positions = pairs_alone.positions = sim.positions
            scale = np.max(np.abs(fresh.forces))
            np.testing.assert_allclose(sim.forces, fresh.forces, rtol=0, atol=1e-9 * scale)
            np.testing.assert_allclose(sim.forces - pairs_alone.forces, np.broadcast_to(gravity, (n, 3)),
                                       rtol=0, atol=1e-9 * scale)


@pytest.mark.parametrize("kind", BOOKKEEPING_CASES)
def test_external_forces_set_after_a_call_act_on_the_next_step(options, kind):
    """With no force field the forces are the host's external forces alone. The drift kernel of the
    last step cleared the force buffer to the external forces it knew; forces set after the call must
    replace them there: read back at once, and pushing the particles in the next step (at temperature
    0 the Brownian displacement is dt F / (6 pi eta a); the inertial integrators' velocities turn
    towards F)."""
    positions, box = perturbed_lattice(3, 1.2, 0.1, seed=4)
    n = len(positions)
    entry = dict(BOOKKEEPING_CASES[kind])
    entry["parameters"] = dict(entry["parameters"], temperature=0.0)
    types = half_light_half_heavy(n)
    doc = document(positions, types, {"integrate": entry}, [("integrate", 1000)], box=box)
    external = np.random.default_rng(8).normal(size=(n, 3))
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        sim.step(2)
        sim.external_forces = external
        np.testing.assert_allclose(sim.forces, external, rtol=0, atol=1e-12)
        before, velocities = sim.positions, sim.velocities
        sim.step(1)
        moved = minimum_image(sim.positions - before, box)
        if kind == "EulerMaruyama":
            dt, viscosity = entry["parameters"]["timeStep"], entry["parameters"]["viscosity"]
            radius = np.array([RADIUS[t] for t in types])[:, None]
            np.testing.assert_allclose(moved, dt * external / (6 * np.pi * viscosity * radius), rtol=1e-9, atol=1e-14)
        else:
            assert np.all(np.einsum("ij,ij->i", sim.velocities - velocities, external) > 0), \
                "every particle is pushed along the new external force"


# ---- reproducibility -----------------------------------------------------------------------------

REPRODUCIBLE = {
    "BBK": langevin("BBK", 0.005, 1.0),
    "GJF": langevin("GJF", 0.005, 1.0),
    "EulerMaruyama": brownian(0.002, 0.5),
}


def lennard_jones_fluid(kind, seed, steps):
    """343 LJ particles at density 0.58: the neighbour lists (skin 0.5) are rebuilt during the run."""
    positions, box = perturbed_lattice(7, 1.2, 0.1, seed=4)
    return document(positions, half_light_half_heavy(len(positions)), {"integrate": REPRODUCIBLE[kind]},
                    [("integrate", steps)], force_field=lennard_jones(), box=box, seed=seed)


def final_state(options, kind, seed, steps=300):
    with structmd.Simulation(options) as sim:
        sim.load(lennard_jones_fluid(kind, seed, steps))
        start = sim.positions
        sim.run()
        return start, sim.positions, sim.velocities, sim.box


@pytest.mark.parametrize("kind", REPRODUCIBLE)
def test_the_same_seed_repeats_the_trajectory_bit_for_bit_on_any_thread_count(options, kind):
    if options["backend"] != "cpu":
        pytest.skip("thread counts are a CPU matter; the CPU run of this suite covers them")
    cpu = {"backend": "cpu", "precision": "double", "log": "quiet"}
    start, one_thread, one_thread_v, box = final_state(dict(cpu, threads=1), kind, seed=21)
    _, two_threads, two_threads_v, _ = final_state(dict(cpu, threads=2), kind, seed=21)
    _, other_seed, _, _ = final_state(dict(cpu, threads=2), kind, seed=22)
    # Some particle moved more than half the skin (0.5 (3.0 - 2.5)), so the lists were rebuilt.
    assert np.max(np.linalg.norm(minimum_image(one_thread - start, box), axis=1)) > 0.25
    assert np.array_equal(one_thread, two_threads) and np.array_equal(one_thread_v, two_threads_v)
    assert np.max(np.abs(minimum_image(other_seed - one_thread, box))) > 0.01, "another seed, another trajectory"


@pytest.mark.parametrize("kind", REPRODUCIBLE)
def test_the_backend_repeats_the_cpu_trajectory_to_rounding(options, kind):
    if options["backend"] == "cpu":
        pytest.skip("compares another backend with the CPU: run with STRUCTMD_TEST_BACKEND=cuda")
    # 100 steps: short enough that the LJ fluid's chaos amplifies rounding differences (1e-16) to
    # far less than 1e-9.
    cpu = {"backend": "cpu", "precision": "double", "log": "quiet"}
    _, expected, expected_v, box = final_state(cpu, kind, seed=21, steps=100)
    _, positions, velocities, _ = final_state(options, kind, seed=21, steps=100)
    np.testing.assert_allclose(minimum_image(positions - expected, box), 0.0, atol=1e-9)
    np.testing.assert_allclose(velocities, expected_v, atol=1e-9)


# ---- per-particle friction and diffusion from the state (UAMMD-structured's particle data) ---------

def with_state_column(doc, label, values):
    doc["state"]["labels"].append(label)
    for row, value in zip(doc["state"]["data"], values):
        row.append(float(value))
    return doc


@pytest.mark.parametrize("kind", ["BBK", "GJF"])
def test_langevin_takes_each_particles_friction_from_the_state_when_the_parameter_is_absent(options, kind):
    """Free particles at T = 0: each velocity decays by (1 - g_i) / (1 + g_i) per step, g_i = gamma_i dt / 2,
    with gamma_i the particle's frictionConstant from the state."""
    n, dt, steps = 6, 0.01, 7
    friction = np.array([0.5, 1.0, 2.0, 4.0, 8.0, 16.0])
    positions = [[2.0 * i - 5.0, 0.0, 0.0] for i in range(n)]
    velocities = np.random.default_rng(3).normal(size=(n, 3))
    entry = {"type": ["Langevin", kind], "parameters": {"timeStep": dt, "temperature": 0.0, "resetVelocities": False}}
    doc = with_state_column(document(positions, ["light"] * n, {"integrate": entry}, [("integrate", steps)],
                                     velocities=velocities), "frictionConstant", friction)
    with structmd.Simulation(options) as sim:
        sim.load(doc)
        sim.run()
        g = 0.5 * friction * dt
        expected = velocities * (((1.0 - g) / (1.0 + g)) ** steps)[:, None]
        np.testing.assert_allclose(sim.velocities, expected, rtol=1e-6 if options.get("precision") == "single" else 1e-12)


def test_brownian_takes_each_particles_self_diffusion_from_the_state_when_the_viscosity_is_absent(options):
    """D_i = k_B T / (6 pi eta a_i) in the state gives the trajectory that viscosity eta gives."""
    positions, box = perturbed_lattice(4, 1.6, 0.25, seed=4)
    n = len(positions)
    types = half_light_half_heavy(n)
    viscosity = 0.7
    diffusion = [KT / (6.0 * math.pi * viscosity * RADIUS[t]) for t in types]
    trajectories = []
    for doc in (document(positions, types, {"integrate": brownian(0.001, viscosity)}, [("integrate", 20)],
                         force_field=lennard_jones(), box=box),
                with_state_column(document(positions, types,
                                           {"integrate": {"type": ["Brownian", "EulerMaruyama"],
                                                          "parameters": {"timeStep": 0.001}}},
                                           [("integrate", 20)], force_field=lennard_jones(), box=box),
                                  "translationalSelfDiffusion", diffusion)):
        with structmd.Simulation(options) as sim:
            sim.load(doc)
            sim.run()
            trajectories.append(sim.positions)
    tolerance = 1e-4 if options.get("precision") == "single" else 1e-10
    np.testing.assert_allclose(minimum_image(trajectories[1] - trajectories[0], box), 0.0, atol=tolerance)
    assert np.any(np.abs(trajectories[0] - np.array(positions)) > 1e-3)


def test_a_missing_friction_or_viscosity_without_the_state_column_names_its_path(options):
    positions = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]]
    for entry, column, message in (
            ({"type": ["Langevin", "BBK"], "parameters": {"timeStep": 0.01}}, None,
             r"integrator\.integrate\.parameters\.frictionConstant: missing.*state column 'frictionConstant'"),
            ({"type": ["Brownian", "EulerMaruyama"], "parameters": {"timeStep": 0.01}}, None,
             r"integrator\.integrate\.parameters\.viscosity: missing.*'translationalSelfDiffusion'"),
            ({"type": ["Brownian", "EulerMaruyama"], "parameters": {"timeStep": 0.01, "temperature": 0.0}},
             "translationalSelfDiffusion", r"integrator\.integrate\.parameters\.temperature.*temperature > 0")):
        doc = document(positions, ["light", "heavy"], {"integrate": entry}, [("integrate", 10)])
        if column:
            with_state_column(doc, column, [1.0, 1.0])
        with structmd.Simulation(options) as sim:
            with pytest.raises(structmd.InputError, match=message):
                sim.load(doc)


# ---- removing global motion (BBK stopTransRotSteps) ----------------------------------------------

def rigid_motion_removed(positions, velocities, masses, dt):
    """Velocities less the rigid motion V + omega x (r - R) that carries the momentum and the angular
    momentum about the centre of mass R, at the positions half a step back (unwrapped)."""
    r = positions - 0.5 * dt * velocities
    m = masses[:, None]
    centre = np.sum(m * r, axis=0) / masses.sum()
    velocity = np.sum(m * velocities, axis=0) / masses.sum()
    d = r - centre
    angular = np.sum(m * np.cross(d, velocities - velocity), axis=0)
    inertia = np.sum(masses[:, None, None] * (np.einsum("ij,ij->i", d, d)[:, None, None] * np.eye(3)
                                              - np.einsum("ia,ib->iab", d, d)), axis=0)
    omega = np.linalg.solve(inertia, angular)
    return velocities - velocity - np.cross(omega, d)


def test_bbk_removes_the_global_translation_and_rotation_every_stop_trans_rot_steps(options):
    """A bonded cluster straddling the box's boundary, in a hot bath, starting without rigid motion
    (so the removal when the stage begins changes nothing): with stopTransRotSteps = 5 the run
    matches the one without up to step 4, and at step 5 its velocities are those of the run without,
    less their rigid motion computed here with numpy on unwrapped positions."""
    if options.get("precision", "double") != "double":
        pytest.skip("compares velocities to 1e-9")
    rng = np.random.default_rng(5)
    n, box, dt = 8, 20.0, 0.005
    whole = np.array([[9.3 + 0.9 * (i % 2), 0.9 * ((i // 2) % 2), 0.9 * (i // 4)] for i in range(n)])
    wrapped = whole.copy()
    wrapped[:, 0] = (wrapped[:, 0] + box / 2) % box - box / 2  # half of the cluster lies at -x
    types = half_light_half_heavy(n)
    masses = np.array([MASS[t] for t in types])
    bonds = {"type": ["Bond2", "HarmonicCommon_K_r0"], "parameters": {"K": 50.0, "r0": 0.9},
             "labels": ["id_i", "id_j"], "data": [[i, j] for i in range(n) for j in range(i + 1, n)]}
    velocities = rigid_motion_removed(whole, rng.normal(0.0, 1.0, size=(n, 3)), masses, 0.0)

    def run(steps, **extra):
        entry = langevin("BBK", dt, 0.5, resetVelocities=False, **extra)
        doc = document(wrapped, types, {"integrate": entry}, [("integrate", 20)],
                       force_field={"bonds": bonds}, box=box, velocities=velocities)
        with structmd.Simulation(options) as sim:
            sim.load(doc)
            sim.step(steps)
            # The cluster, a sigma across, stays whole around where particle 0 started.
            return whole[0] + minimum_image(sim.positions - whole[0], box), sim.velocities

    _, free4 = run(4)
    _, stopped4 = run(4, stopTransRotSteps=5)
    np.testing.assert_allclose(stopped4, free4, atol=1e-9)
    x5, free5 = run(5)
    _, stopped5 = run(5, stopTransRotSteps=5)
    expected = rigid_motion_removed(x5, free5, masses, dt)
    assert np.linalg.norm(free5 - expected) > 1e-2, "the bath gave the cluster some rigid motion to remove"
    np.testing.assert_allclose(stopped5, expected, atol=1e-9)
    assert np.linalg.norm(np.sum(masses[:, None] * stopped5, axis=0)) < 1e-10


# ---- input errors --------------------------------------------------------------------------------

@pytest.mark.parametrize("entry, error, message", [
    ({"type": ["SteepestDescent", "SteepestDescent"],
      "parameters": {"h": 0.01, "maxObjectiveForce": 1.0, "nStepsPrintProgress": -2}}, structmd.InputError,
     r"integrator\.integrate\.parameters\.nStepsPrintProgress"),
    (langevin("BBK", 0.01, 1.0, stopTransRotSteps=-1), structmd.InputError,
     r"integrator\.integrate\.parameters\.stopTransRotSteps"),
    (langevin("GJF", 0.01, -1.0), structmd.InputError, r"integrator\.integrate\.parameters\.frictionConstant"),
    ({"type": ["SteepestDescent", "SteepestDescent"], "parameters": {"h": 0.01}}, structmd.InputError,
     r"integrator\.integrate\.parameters\.maxObjectiveForce"),
    ({"type": ["Langevin", "BBK"], "parameters": {"frictionConstant": 1.0}}, structmd.InputError,
     r"integrator\.integrate\.parameters\.timeStep"),
    (langevin("BBK", 0.01, 1.0, group="nobody"), structmd.InputError,
     r"integrator\.integrate\.parameters\.group.*nobody"),
    ({"type": ["Langevin", "Foo"], "parameters": {"timeStep": 0.01}}, structmd.InputError,
     r'(?s)integrator\.integrate\.type.*\["Langevin", "GJF"\]'),
])
def test_malformed_integrators_name_their_path(options, entry, error, message):
    doc = document([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]], ["light", "heavy"], {"integrate": entry}, [("integrate", 10)])
    with structmd.Simulation(options) as sim:
        with pytest.raises(error, match=message):
            sim.load(doc)
