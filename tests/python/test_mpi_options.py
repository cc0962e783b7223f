"""The handle's "mpi_comm" option and structmd_get_info's "mpi" from a process that never initialises
MPI: the info says whether MPI is compiled in (one rank, rank 0, without a communicator), a value that
is not an integer is an argument error naming the option, and an integer is refused as the build
dictates: "MPI is not compiled in" (STRUCTMD_ERR_UNSUPPORTED) without MPI, and "not initialised"
(STRUCTMD_ERR_STATE) with it, since the library leaves MPI_Init to the host. The MPI runs themselves
are tests/mpi (label mpi)."""

import pytest

import structmd


def test_info_says_whether_mpi_is_compiled_in():
    with structmd.Simulation({"backend": "cpu"}) as sim:
        mpi = sim.info["mpi"]
    assert isinstance(mpi["compiled"], bool)
    assert mpi["ranks"] == 1 and mpi["rank"] == 0 and mpi["node_rank"] == 0


@pytest.mark.parametrize("value", ["0", 1.5, [0], None])
def test_mpi_comm_must_be_an_integer(value):
    with pytest.raises(structmd.ArgumentError, match='option "mpi_comm": expected an integer'):
        structmd.Simulation({"backend": "cpu", "mpi_comm": value})


def test_mpi_comm_without_mpi_init_or_without_mpi():
    with structmd.Simulation({"backend": "cpu"}) as sim:
        compiled = sim.info["mpi"]["compiled"]
    if compiled:
        with pytest.raises(structmd.StateError, match="MPI is not initialised"):
            structmd.Simulation({"backend": "cpu", "mpi_comm": 0})
    else:
        with pytest.raises(structmd.UnsupportedError, match="MPI is not compiled in"):
            structmd.Simulation({"backend": "cpu", "mpi_comm": 0})


def test_info_says_whether_nccl_is_compiled_in():
    with structmd.Simulation({"backend": "cpu"}) as sim:
        mpi = sim.info["mpi"]
    assert isinstance(mpi["nccl"], bool)
    # NCCL is only built with MPI (and CUDA).
    assert mpi["compiled"] or not mpi["nccl"]


@pytest.mark.parametrize("value", ["gpu", "", 1, None])
def test_ghost_exchange_takes_auto_host_or_nccl(value):
    with pytest.raises(structmd.ArgumentError, match='option "ghost_exchange": expected'):
        structmd.Simulation({"backend": "cpu", "ghost_exchange": value})


@pytest.mark.parametrize("value", ["auto", "host"])
def test_ghost_exchange_through_the_host_suits_any_backend(value):
    with structmd.Simulation({"backend": "cpu", "ghost_exchange": value}) as sim:
        assert sim.info["backend"] == "cpu"


def test_nccl_ghost_exchange_needs_nccl_and_gpus():
    with structmd.Simulation({"backend": "cpu"}) as sim:
        nccl = sim.info["mpi"]["nccl"]
    if nccl:
        with pytest.raises(structmd.ArgumentError, match='"nccl" sends ghosts between GPUs'):
            structmd.Simulation({"backend": "cpu", "ghost_exchange": "nccl"})
    else:
        with pytest.raises(structmd.UnsupportedError, match="this build of structmd has no NCCL"):
            structmd.Simulation({"backend": "cpu", "ghost_exchange": "nccl"})
