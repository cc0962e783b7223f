#pragma once
// What every structmd call must honour whatever the fuzzer feeds it; a breach aborts, which libFuzzer
// reports as a crash with the input that caused it.
#include <cstdio>
#include <cstdlib>

#include "structmd.h"

namespace structmd::fuzz {

// One CPU thread: runs are fast and reproducible, and OpenMP adds no threads for ASan to track.
inline const char* const kHandleOptions = R"({"backend": "cpu", "threads": 1, "log": "quiet"})";

[[noreturn]] inline void breach(const char* call, structmd_status status, const char* what, const char* message) {
    std::fprintf(stderr, "contract breach in %s (status %d): %s\nmessage: %s\n", call, static_cast<int>(status), what,
                 message ? message : "(null)");
    std::abort();
}

// A status from the header's list, never STRUCTMD_ERR_INTERNAL (a bug by definition), and a
// non-empty message after any failure. sim may be NULL: the message is then the thread's.
inline structmd_status checked(const char* call, structmd_status status, const structmd_sim* sim) {
    const char* message = structmd_last_error(sim);
    if (status < STRUCTMD_OK || status > STRUCTMD_ERR_INTERNAL) breach(call, status, "unknown status", message);
    if (status == STRUCTMD_ERR_INTERNAL) breach(call, status, "internal error", message);
    if (status != STRUCTMD_OK && (message == nullptr || message[0] == '\0'))
        breach(call, status, "failure without a message", message);
    return status;
}

}  // namespace structmd::fuzz
