#pragma once
// What a backend counts for its handle. Bytes copied between the host and a backend's buffers, counted by the backend itself so that a
// test can prove the step loop moves no particle data. On the CPU backend these are the copies
// between the caller's arrays and the engine's own.
#include <cstdint>

namespace structmd {

struct TransferCounters {
    uint64_t hostToDevice = 0;
    uint64_t deviceToHost = 0;
};

// Bytes a handle's buffers hold on its backend now; each buffer gives back what it took when it is
// released, so the figure follows resizes and destruction.
struct MemoryAccount {
    int64_t bytes = 0;
};

}  // namespace structmd
