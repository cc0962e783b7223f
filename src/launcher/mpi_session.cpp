#include "mpi_session.hpp"

#include <cstdlib>
#include <stdexcept>

#ifdef STRUCTMD_HAVE_MPI
// The C interface only: MPI's deprecated C++ bindings are not used.
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>
#endif

namespace structmd::launcher {

bool MpiSession::requested(bool flag) {
    for (const char* variable : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
        if (std::getenv(variable)) return true;
    return flag;
}

#ifdef STRUCTMD_HAVE_MPI

bool MpiSession::compiled() { return true; }

MpiSession::MpiSession(int* argc, char*** argv) {
    int initialised = 0;
    MPI_Initialized(&initialised);
    if (!initialised) {
        if (MPI_Init(argc, argv) != MPI_SUCCESS) throw std::runtime_error("MPI_Init failed");
        initialisedHere_ = true;
    }
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
    worldHandle_ = static_cast<int64_t>(MPI_Comm_c2f(MPI_COMM_WORLD));
}

MpiSession::~MpiSession() {
    if (initialisedHere_) MPI_Finalize();
}

int64_t MpiSession::rank0_value(int64_t value) const {
    MPI_Bcast(&value, 1, MPI_INT64_T, 0, MPI_COMM_WORLD);
    return value;
}

#else

bool MpiSession::compiled() { return false; }

MpiSession::MpiSession(int*, char***) { throw std::runtime_error("MPI is not compiled in"); }

MpiSession::~MpiSession() = default;

int64_t MpiSession::rank0_value(int64_t value) const { return value; }

#endif

}  // namespace structmd::launcher
