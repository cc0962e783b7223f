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
