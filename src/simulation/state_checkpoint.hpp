#pragma once
// The dynamic state a checkpoint holds, and its byte layout inside the checkpoint file
// (checkpoint_file.hpp). Host code, compiled once per precision (state_checkpoint.cpp).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/box.hpp"
#include "core/vec.hpp"

namespace structmd {

template <class R>
struct DynamicState {
    int64_t firstStep = 0;  // where the schedule starts: a checkpoint fits only its own input
    int64_t step = 0;
    double time = 0.0;
    int32_t activeStage = -1;
    std::array<double, 3> box{};
    double lambda = 1.0;  // the ensemble's coupling parameter, which simulation steps change
    std::vector<Real4<R>> pos, vel;
    std::vector<Image> image;
    std::vector<Real4<R>> externalForce;  // empty when the host set none
    std::vector<Real4<R>> dir;            // orientations; empty when the simulation has none
    std::vector<Real4<R>> magnetization;  // magnetic moments; empty when the simulation has none
    std::vector<std::vector<double>> integrators;
};

template <class R>
std::vector<unsigned char> encode_state(const DynamicState<R>& state);

// What the simulation a checkpoint is loaded into looks like; a checkpoint that does not fit it, or
// holds a state the load and the setters would refuse (a box beyond range or shorter than twice the
// cutoff, a type out of range, a time, position, velocity or mass that is not finite), is ERR_IO
// naming the path and what is wrong, before anything changes.
struct StateShape {
    std::string precision;  // "single", "mixed" or "double", for the message
    int64_t particles = 0;
    int64_t firstStep = 0;
    int64_t finalStep = 0;
    int stages = 0;
    size_t integrators = 0;
    int types = 0;
    double largestCutoff = 0.0;  // of the pair terms
};

template <class R>
DynamicState<R> decode_state(const std::vector<unsigned char>& payload, const std::string& path, const StateShape& shape);

}  // namespace structmd
