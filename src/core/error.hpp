#pragma once
// The engine's one exception type. It carries the C status code it maps to, so the API barrier in
// src/api/ can turn any failure into (status, message) without guessing.
#include <stdexcept>
#include <string>

#include "structmd.h"

namespace structmd {

class Error : public std::runtime_error {
public:
    Error(structmd_status status, const std::string& message)
        : std::runtime_error(message), status_(status) {}
    structmd_status status() const noexcept { return status_; }

private:
    structmd_status status_;
};

// Inconsistent or malformed input; the message starts with the JSON path of the culprit.
inline Error input_error(const std::string& path, const std::string& what) {
    return Error(STRUCTMD_ERR_INPUT, (path.empty() ? std::string("(document)") : path) + ": " + what);
}

}  // namespace structmd
