#pragma once
// The launcher's MPI: under mpirun (or with --mpi) it initialises MPI, hands MPI_COMM_WORLD to the
// engine as the handle's "mpi_comm", lets rank 0 alone print, and finalises MPI at the end. The
// library never initialises MPI itself: here the launcher is the host program that owns it.
#include <cstdint>
#include <string>

namespace structmd::launcher {

class MpiSession {
public:
    // Whether MPI is asked for: --mpi, or the environment an MPI launcher (Open MPI's mpirun, a
    // PMI or PMIx process manager such as MPICH's Hydra or Slurm's srun) gives its processes.
    static bool requested(bool flag);
    static bool compiled();

    // Initialises MPI (unless something already did); only where compiled() is true.
    MpiSession(int* argc, char*** argv);
    ~MpiSession();
    MpiSession(const MpiSession&) = delete;
    MpiSession& operator=(const MpiSession&) = delete;

    int rank() const { return rank_; }
    int size() const { return size_; }
    int64_t world_handle() const { return worldHandle_; }  // MPI_Comm_c2f(MPI_COMM_WORLD)
    // Rank 0's value on every rank: the launcher's choices that every rank must share (how many
    // steps a structmd_step call takes).
    int64_t rank0_value(int64_t value) const;

private:
    int rank_ = 0;
    int size_ = 1;
    int64_t worldHandle_ = 0;
    bool initialisedHere_ = false;
};

}  // namespace structmd::launcher
