/*
 * structmd.hpp - optional C++ conveniences over the C ABI of structmd.h, header-only: a handle that
 * destroys itself, failures as exceptions on the host's side, and structmd_get_info as text. It adds
 * nothing to the binary interface; the library never throws across it.
 */
#ifndef STRUCTMD_HPP
#define STRUCTMD_HPP

#include <stdexcept>
#include <string>

#include "structmd.h"

namespace structmd::host {

/** A failed call: which function, its status and the library's message. */
class Failure : public std::runtime_error {
public:
    Failure(std::string call, structmd_status status, const std::string& message)
        : std::runtime_error(call + ": " + message), call_(std::move(call)), status_(status) {}
    const std::string& call() const noexcept { return call_; }
    structmd_status status() const noexcept { return status_; }

private:
    std::string call_;
    structmd_status status_;
};

/** Throws Failure when status is not STRUCTMD_OK; sim may be NULL for structmd_create. */
inline void check(structmd_status status, const structmd_sim* sim, const char* call) {
    if (status != STRUCTMD_OK) throw Failure(call, status, structmd_last_error(sim));
}

/** Owns a handle, so every exit path destroys it (and closes the files it holds). */
class Handle {
public:
    explicit Handle(const std::string& options_json = "") {
        check(structmd_create(options_json.c_str(), &sim_), nullptr, "structmd_create");
    }
    ~Handle() { structmd_destroy(sim_); }
    Handle(const Handle&) = delete;
    Handle& operator=(const Handle&) = delete;

    structmd_sim* get() const { return sim_; }

private:
    structmd_sim* sim_ = nullptr;
};

/** The JSON text of structmd_get_info, whatever its length. */
inline std::string info(const structmd_sim* sim) {
    size_t needed = 0;
    structmd_get_info(sim, nullptr, 0, &needed);
    std::string text(needed, '\0');
    check(structmd_get_info(sim, &text[0], text.size(), &needed), sim, "structmd_get_info");
    text.resize(needed - 1);
    return text;
}

}  // namespace structmd::host

#endif /* STRUCTMD_HPP */
