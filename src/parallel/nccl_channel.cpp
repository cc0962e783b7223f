// NCCL's point-to-point calls over the ranks of the handle's MPI communicator.
#include "parallel/nccl_channel.hpp"

#include <cuda_runtime_api.h>
#include <nccl.h>

#include <algorithm>
#include <string>

#include "core/error.hpp"

namespace structmd {

namespace {

void nccl_check(ncclResult_t result, const char* what) {
    if (result != ncclSuccess)
        throw Error(STRUCTMD_ERR_DEVICE, std::string("NCCL, ") + what + ": " + ncclGetErrorString(result));
}

}  // namespace

struct NcclChannel::Comm {
    ncclComm_t comm = nullptr;
    ~Comm() {
        if (comm) ncclCommDestroy(comm);
    }
};

NcclChannel::NcclChannel(const Communicator& mpi) : comm_(std::make_unique<Comm>()) {
    ncclUniqueId id{};
    std::string bytes;
    if (mpi.rank() == 0) {
        nccl_check(ncclGetUniqueId(&id), "making the communicator's id");
        bytes.assign(reinterpret_cast<const char*>(&id), sizeof id);
    }
    mpi.broadcast(bytes, 0);
    if (bytes.size() != sizeof id) throw Error(STRUCTMD_ERR_INTERNAL, "NCCL's id arrived with a wrong size");
    std::copy(bytes.begin(), bytes.end(), reinterpret_cast<char*>(&id));
    nccl_check(ncclCommInitRank(&comm_->comm, mpi.size(), id, mpi.rank()), "joining the communicator");
}

NcclChannel::~NcclChannel() = default;

void NcclChannel::shift(const std::vector<Shift>& shifts, void* stream) {
    const auto s = static_cast<cudaStream_t>(stream);
    nccl_check(ncclGroupStart(), "starting a group");
    // Both sides know each count (the rebuild exchanged them), so an empty transfer is skipped on both.
    for (const Shift& shift : shifts) {
        if (shift.sentBytes > 0)
            nccl_check(ncclSend(shift.sent, shift.sentBytes, ncclChar, shift.to, comm_->comm, s), "sending ghosts");
        if (shift.receivedBytes > 0)
            nccl_check(ncclRecv(shift.received, shift.receivedBytes, ncclChar, shift.from, comm_->comm, s),
                       "receiving ghosts");
    }
    nccl_check(ncclGroupEnd(), "ending a group");
}

}  // namespace structmd
