"""Force callbacks and zero-copy views through the Python package: a Lennard-Jones liquid whose pair
forces come from a host callback follows the trajectory of the built-in term; a callback's exception
stops the step and rolls it back; device callbacks and DLPack views see the engine's own memory (numpy
on the CPU backend, CuPy and PyTorch on CUDA, each skipped where it is not installed)."""

import numpy as np
import pytest

import structmd
from conftest import BACKEND
from test_coupling import lattice

CUTOFF = 2.5


def lennard_jones(positions, box, pairs_to_skip=()):
    """Forces, energy and virial sum r_ij (x) F_ij of LJ (epsilon = sigma = 1, unshifted, cut at
    CUTOFF) over all pairs by minimum image: an independent O(n^2) evaluation in double."""
    d = positions[:, None, :] - positions[None, :, :]
    d -= box * np.round(d / box)
    r2 = np.einsum("ijk,ijk->ij", d, d)
    np.fill_diagonal(r2, np.inf)
    for i, j in pairs_to_skip:
        r2[i, j] = r2[j, i] = np.inf
    inside = r2 < CUTOFF ** 2
    inv6 = np.where(inside, 1.0 / r2 ** 3, 0.0)
    energy = 0.5 * np.sum(np.where(inside, 4 * (inv6 ** 2 - inv6), 0.0))
    scale = np.where(inside, 24 * (2 * inv6 ** 2 - inv6) / r2, 0.0)
    pair_forces = scale[:, :, None] * d  # on i from j
    virial = 0.5 * np.einsum("ijk,ijl->kl", d, pair_forces)
    return pair_forces.sum(axis=1), energy, virial


def liquid_without_lj():
    doc = lattice(side=5, steps=100)
    del doc["topology"]["forceField"]["lj"]
    del doc["topology"]["forceField"]["nl"]
    return doc


@pytest.fixture
def make(options):
    made = []

    def new(doc):
        sim = structmd.Simulation(options)
        sim.load(doc)
        made.append(sim)
        return sim

    yield new
    for sim in made:
        sim.close()


def test_lennard_jones_by_callback_follows_the_built_in_term(make):
    built_in = make(lattice(side=5, steps=100))
    by_callback = make(liquid_without_lj())
    box = np.array(by_callback.box)

    def pair_forces(positions, forces, step):
        f, energy, virial = lennard_jones(positions, box)
        forces += f
        return energy, virial

    by_callback.set_force_callback(pair_forces)
    np.testing.assert_allclose(by_callback.forces, built_in.forces, rtol=1e-10, atol=1e-10)
    assert by_callback.energy("callback") == pytest.approx(built_in.energy("lj"), rel=1e-12)
    assert by_callback.energy("potential") == pytest.approx(built_in.energy("potential"), rel=1e-12)
    np.testing.assert_allclose(by_callback.virial, built_in.virial, rtol=1e-10, atol=1e-10)
    assert by_callback.pressure == pytest.approx(built_in.pressure, rel=1e-10)
    built_in.step(50)
    by_callback.step(50)
    np.testing.assert_allclose(by_callback.positions, built_in.positions, rtol=0, atol=1e-9)
    assert by_callback.energy("total") == pytest.approx(built_in.energy("total"), rel=1e-10)


def test_exception_in_callback_is_a_callback_error_and_the_step_is_undone(make):
    sim = make(lattice(side=5, steps=100))
    sim.step(3)
    positions, velocities = sim.positions, sim.velocities

    def failing(positions, forces, step):
        if step == 6:
            raise ValueError("the QM region did not converge")

    sim.set_force_callback(failing)
    with pytest.raises(structmd.CallbackError) as caught:
        sim.step(10)
    assert "ValueError: the QM region did not converge" in str(caught.value)
    assert caught.value.status == structmd.STATUS["STRUCTMD_ERR_CALLBACK"]
    assert sim.step_number == 3
    np.testing.assert_array_equal(sim.positions, positions)
    np.testing.assert_array_equal(sim.velocities, velocities)
    sim.set_force_callback(None)
    sim.step(10)
    assert sim.step_number == 13


def test_non_finite_force_from_callback_is_refused(make):
    sim = make(lattice(side=5, steps=100))

    def broken(positions, forces, step):
        forces[7, 1] = np.nan

    sim.set_force_callback(broken)
    with pytest.raises(structmd.CallbackError, match="particle id 7"):
        sim.step(1)
    assert sim.step_number == 0


def harmonic_trap(positions, forces, k=2.0):
    forces -= k * positions
    return 0.5 * k * float(np.sum(positions ** 2))


def test_device_callback_on_the_cpu_backend_matches_the_host_callback(make):
    if BACKEND != "cpu":
        pytest.skip("view.numpy() reads host memory: CPU backend only (the CUDA variant uses CuPy)")
    host = make(lattice(side=5, steps=200))
    device = make(lattice(side=5, steps=200))
    host.set_force_callback(lambda positions, forces, step: harmonic_trap(positions, forces))

    def on_records(positions, forces, step, stream):
        assert stream == 0 and positions.shape == (125, 3)
        return harmonic_trap(positions.numpy(), forces.numpy())

    device.set_device_force_callback(on_records)
    host.step(100)
    device.step(100)
    np.testing.assert_array_equal(device.positions, host.positions)
    assert device.energy("callback") == host.energy("callback")


def test_views_share_the_engines_memory_on_the_cpu_backend(make):
    if BACKEND != "cpu":
        pytest.skip("numpy reads only host memory")
    sim = make(lattice(side=5, steps=100))
    for name, values in (("positions", sim.positions), ("velocities", sim.velocities), ("forces", sim.forces)):
        view = sim.view(name)
        array = np.from_dlpack(view)
        assert array.shape == values.shape and array.dtype == np.float64
        np.testing.assert_array_equal(array, values)
        assert array.__array_interface__["data"][0] == view.data_pointer
    again = sim.positions_view()
    assert again.data_pointer == sim.positions_view().data_pointer
    with pytest.raises(structmd.ArgumentError, match="known: positions, velocities, forces"):
        sim.view("masses")


def test_a_view_of_a_closed_simulation_raises_instead_of_reading_freed_memory(make):
    if BACKEND != "cpu":
        pytest.skip("numpy reads only host memory")
    sim = make(lattice(side=5, steps=100))
    view, unread = sim.positions_view(), sim.forces_view()
    np.testing.assert_array_equal(view.numpy(), sim.positions)
    sim.close()
    with pytest.raises(structmd.StateError, match="closed"):
        view.numpy()
    with pytest.raises(structmd.StateError, match="closed"):
        np.from_dlpack(unread)


def cuda_module(name):
    if BACKEND != "cuda":
        pytest.skip("needs the CUDA backend")
    return pytest.importorskip(name)


def test_cupy_and_torch_read_views_without_a_copy(make):
    cupy = cuda_module("cupy")
    sim = make(lattice(side=5, steps=100))
    sim.step(5)
    view = sim.positions_view()
    array = cupy.from_dlpack(view)
    assert array.data.ptr == view.data_pointer
    np.testing.assert_array_equal(cupy.asnumpy(array), sim.positions)
    torch = pytest.importorskip("torch")
    forces = torch.utils.dlpack.from_dlpack(sim.forces_view())
    np.testing.assert_array_equal(forces.cpu().numpy(), sim.forces)


def test_device_callback_with_cupy_matches_the_host_callback(make):
    cupy = cuda_module("cupy")
    host = make(lattice(side=5, steps=200))
    device = make(lattice(side=5, steps=200))
    host.set_force_callback(lambda positions, forces, step: harmonic_trap(positions, forces))

    def on_device(positions, forces, step, stream):
        with cupy.cuda.ExternalStream(stream):
            x = cupy.from_dlpack(positions)
            f = cupy.from_dlpack(forces)
            f -= 2.0 * x
            return float(cupy.sum(x * x))

    device.set_device_force_callback(on_device)
    host.step(100)
    device.step(100)
    np.testing.assert_allclose(device.positions, host.positions, rtol=0, atol=1e-12)
    assert device.energy("callback") == pytest.approx(host.energy("callback"), rel=1e-12)
