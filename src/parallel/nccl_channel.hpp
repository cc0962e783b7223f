#pragma once
// Ghost positions sent from GPU to GPU through NCCL (built with STRUCTMD_HAVE_NCCL): the sends and
// receives of a refresh are queued on the engine's stream, so a spatial domain's step neither copies
// its border through the host nor waits for the GPU to exchange it. The communicator's ranks are
// NCCL's; the view (parallel/domains_over_ranks.hpp) makes the channel at the first refresh, when
// the engine's GPU is the current one.
#include <cstddef>
#include <memory>
#include <vector>

#include "parallel/communicator.hpp"

namespace structmd {

class NcclChannel {
public:
    // Collective over `comm`: rank 0's NCCL id is broadcast over MPI and every rank joins it on the
    // current GPU. Throws ERR_DEVICE naming NCCL's error.
    explicit NcclChannel(const Communicator& comm);
    ~NcclChannel();
    NcclChannel(const NcclChannel&) = delete;
    NcclChannel& operator=(const NcclChannel&) = delete;

    // `sentBytes` from device memory `sent` to rank `to`, and `receivedBytes` from rank `from` into
    // `received`, as every rank calls it with its own partners (a shift along a ring of ranks).
    struct Shift {
        const void* sent;
        size_t sentBytes;
        int to;
        void* received;
        size_t receivedBytes;
        int from;
    };
    // All of `shifts` at once, queued on `stream` (a cudaStream_t): the host does not wait.
    void shift(const std::vector<Shift>& shifts, void* stream);

private:
    struct Comm;
    std::unique_ptr<Comm> comm_;
};

}  // namespace structmd
