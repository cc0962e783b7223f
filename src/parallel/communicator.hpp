#pragma once
// The MPI communicator a handle works over (its "mpi_comm" option), behind an interface free of
// mpi.h so that the rest of the library builds the same with or without MPI. Every call is
// collective: all ranks of the communicator make it, in the same order.
#include <cstdint>
#include <memory>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/error.hpp"

namespace structmd {

class Communicator {
public:
    virtual ~Communicator() = default;

    virtual int rank() const = 0;
    virtual int size() const = 0;
    // This rank's place among the communicator's ranks on its own node (those that share memory):
    // which of the node's GPUs it takes.
    virtual int node_rank() const = 0;

    // counts[r] values from rank r, concatenated in rank order into every rank's `all`.
    virtual void all_gather(const double* mine, double* all, const std::vector<int64_t>& counts) const = 0;
    virtual void all_gather(const int32_t* mine, int32_t* all, const std::vector<int64_t>& counts) const = 0;
    // values[0..n) summed over the ranks, in place on every rank.
    virtual void all_sum(double* values, int n) const = 0;
    virtual int64_t all_min(int64_t value) const = 0;
    virtual int64_t all_max(int64_t value) const = 0;
    // Root's bytes (resized on the other ranks) to every rank.
    virtual void broadcast(std::string& bytes, int root) const = 0;
    // n values to rank `partner` and n from it, into theirs (a pairwise exchange: only the two call it).
    virtual void send_receive(const double* mine, double* theirs, int64_t n, int partner) const = 0;
    // n values to rank `to` and m from rank `from`, into `received` (a shift along a ring of ranks:
    // every rank calls it at once with its own partners; `to` == `from` == this rank copies).
    virtual void shift(const double* sent, int64_t n, int to, double* received, int64_t m, int from) const = 0;
    // The same for n and m bytes.
    virtual void shift(const unsigned char* sent, int64_t n, int to, unsigned char* received, int64_t m,
                       int from) const = 0;
};

// Runs `local` on every rank of `comm`; when it throws on any, every rank throws the error of the
// first rank it failed on (its status and message), so that no rank goes on to a collective call
// the others never make.
template <class F>
void run_together(const Communicator& comm, F&& local) {
    structmd_status status = STRUCTMD_OK;
    std::string message;
    try {
        local();
    } catch (const Error& e) {
        status = e.status();
        message = e.what();
    } catch (const std::bad_alloc&) {
        status = STRUCTMD_ERR_MEMORY;
        message = "out of host memory";
    } catch (const std::exception& e) {
        status = STRUCTMD_ERR_INTERNAL;
        message = std::string("internal error, please report: ") + e.what();
    }
    const int64_t first = comm.all_min(status != STRUCTMD_OK ? comm.rank() : comm.size());
    if (first == comm.size()) return;
    std::string report = std::to_string(static_cast<int>(status)) + " " + message;
    comm.broadcast(report, static_cast<int>(first));
    const size_t space = report.find(' ');
    const auto code = static_cast<structmd_status>(std::stoi(report.substr(0, space)));
    std::string text = report.substr(space + 1);
    if (comm.rank() != first) text += " (on MPI rank " + std::to_string(first) + ")";
    throw Error(code, text);
}

// Whether this library was built with MPI (CMake option STRUCTMD_MPI).
bool mpi_compiled();

// One process alone: what a handle without "mpi_comm" runs over (parallel tempering with every
// replica in this process).
std::shared_ptr<const Communicator> single_process();

// The communicator of a Fortran handle (MPI_Comm_c2f of the host's MPI_Comm). Throws
// ERR_UNSUPPORTED without MPI compiled in, ERR_STATE when MPI is not initialised (the host owns
// MPI_Init and MPI_Finalize), ERR_ARGUMENT for a null communicator.
std::shared_ptr<const Communicator> communicator_from_fortran(int64_t handle);

}  // namespace structmd
