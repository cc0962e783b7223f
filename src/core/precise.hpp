#pragma once
// All the digits a double needs (%.17g), so that two numbers that differ never print alike: for
// messages that quote a value and for source text that must give it back exactly.
#include <cstdio>
#include <string>

namespace structmd {

inline std::string precise(double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", x);
    return text;
}

}  // namespace structmd
