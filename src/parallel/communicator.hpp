#pragma once
// The MPI communicator a handle works over (its "mpi_comm" option), behind an interface free of
// mpi.h so that the rest of the library builds the same with or without MPI. Every call is
// collective: all ranks of the communicator make it, in the same order.
#include <algorithm>
#include <cstdint>
#include <memory>
#include <new>
#include <stdexcept>
#include <string>
#include <utility>
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

// `local`, with what it threw turned into a status and a message (STRUCTMD_OK if nothing).
template <class F>
std::pair<structmd_status, std::string> attempt(F&& local) {
    try {
        local();
    } catch (const Error& e) {
        return {e.status(), e.what()};
    } catch (const std::bad_alloc&) {
        return {STRUCTMD_ERR_MEMORY, "out of host memory"};
    } catch (const std::exception& e) {
        return {STRUCTMD_ERR_INTERNAL, std::string("internal error, please report: ") + e.what()};
    }
    return {STRUCTMD_OK, {}};
}

// Every rank throws the error of rank `first`, the first that failed (its status and message, as
// that rank passes them), unless `first` is the communicator's size: none failed. Collective.
void raise_first_failure(const Communicator& comm, int64_t first, structmd_status status, const std::string& message);

// Runs `local` on every rank of `comm`; when it throws on any, every rank throws the error of the
// first rank it failed on (its status and message), so that no rank goes on to a collective call
// the others never make.
template <class F>
void run_together(const Communicator& comm, F&& local) {
    const auto [status, message] = attempt(local);
    raise_first_failure(comm, comm.all_min(status != STRUCTMD_OK ? comm.rank() : comm.size()), status, message);
}

// The same for a `local` that returns a number: returns its largest value over the ranks, found in
// the same collective call that shares the failures (a step loop's one call a step).
template <class F>
double run_together_max(const Communicator& comm, F&& local) {
    double value = 0.0;
    const auto [status, message] = attempt([&] { value = local(); });
    const int ranks = comm.size();
    const double mine[2] = {static_cast<double>(status != STRUCTMD_OK ? comm.rank() : ranks), value};
    std::vector<double> all(2 * static_cast<size_t>(ranks));
    comm.all_gather(mine, all.data(), std::vector<int64_t>(static_cast<size_t>(ranks), 2));
    int64_t first = ranks;
    double largest = value;
    for (int r = 0; r < ranks; ++r) {
        first = std::min(first, static_cast<int64_t>(all[2 * static_cast<size_t>(r)]));
        largest = std::max(largest, all[2 * static_cast<size_t>(r) + 1]);
    }
    raise_first_failure(comm, first, status, message);
    return largest;
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
