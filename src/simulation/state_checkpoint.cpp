#include "simulation/state_checkpoint.hpp"

#include <cmath>

#include "core/error.hpp"
#include "core/precise.hpp"
#include "forcefield/forcefield_spec.hpp"
#include "simulation/checkpoint_file.hpp"

namespace structmd {

namespace {

template <class T>
void put_vector(ByteWriter& out, const std::vector<T>& values) {
    out.put_bytes(values.data(), values.size() * sizeof(T));
}

// A count read from the file is checked against what the file holds before anything is allocated.
template <class T>
std::vector<T> get_vector(ByteReader& in, size_t count) {
    if (count > in.remaining() / sizeof(T))
        throw Error(STRUCTMD_ERR_IO, "checkpoint '" + in.path() + "': the payload ends early");
    std::vector<T> values(count);
    in.get_bytes(values.data(), count * sizeof(T));
    return values;
}

// The values of a checkpoint pass the checks of the load and of the setters: a file with a valid
// checksum may still have been edited, and a box shorter than twice the cutoff or a NaN position
// would otherwise run (energies of 1e12, NaN forces) or index past the type tables.
template <class R>
void check_state_values(const DynamicState<R>& s, const std::string& path, const StateShape& shape) {
    const auto invalid = [&](const std::string& what) {
        return Error(STRUCTMD_ERR_IO, "checkpoint '" + path + "' holds a state this simulation refuses: " + what);
    };
    for (int d = 0; d < 3; ++d)
        if (!is_box_length(s.box[d]))
            throw invalid("box length " + std::to_string(d) + " is " + precise(s.box[d]) +
                          ", expected > 0 and <= 1e15, or infinity (an open axis)");
    if (!cutoff_fits_box(shape.largestCutoff, s.box))
        throw invalid("the largest cutoff (" + precise(shape.largestCutoff) + ") must be shorter than half the box (" +
                      precise(half_shortest_edge(s.box[0], s.box[1], s.box[2])) + ")");
    if (!std::isfinite(s.time)) throw invalid("the time is " + precise(s.time));
    const auto finite = [](const Real4<R>& v) {
        return std::isfinite(double(v.x)) && std::isfinite(double(v.y)) && std::isfinite(double(v.z));
    };
    for (size_t i = 0; i < s.pos.size(); ++i) {
        const std::string particle = "particle id " + std::to_string(i);
        bool inRange = finite(s.pos[i]);
        for (int d = 0; d < 3 && inRange; ++d)
            inRange = std::fabs(double((&s.pos[i].x)[d])) <= 1e8 * s.box[d];
        if (!inRange) throw invalid("the position of " + particle + " is not finite or lies beyond 1e8 box lengths");
        const double type = s.pos[i].w;
        if (!(type >= 0 && type < shape.types && type == std::floor(type)))
            throw invalid("the type of " + particle + " is " + precise(type) + ", expected an index below " +
                          std::to_string(shape.types));
        if (!finite(s.vel[i]) || !(s.vel[i].w >= 0 && std::isfinite(double(s.vel[i].w))))
            throw invalid("the velocity or mass of " + particle + " is not finite");
    }
    for (const auto* perParticle : {&s.externalForce, &s.dir, &s.magnetization})
        for (size_t i = 0; i < perParticle->size(); ++i)
            if (!finite((*perParticle)[i]) || !std::isfinite(double((*perParticle)[i].w)))
                throw invalid("the external force, orientation or magnetic moment of particle id " + std::to_string(i) +
                              " is not finite");
}

// The optional per-particle arrays after the integrators' state, in this order.
constexpr uint8_t kOrientationsTag = 1;
constexpr uint8_t kMagnetizationTag = 2;

}  // namespace

template <class R>
std::vector<unsigned char> encode_state(const DynamicState<R>& s) {
    ByteWriter out;
    out.put(static_cast<uint32_t>(sizeof(R)));
    out.put(static_cast<int64_t>(s.pos.size()));
    out.put(s.firstStep);
    out.put(s.step);
    out.put(s.time);
    out.put(s.activeStage);
    for (double length : s.box) out.put(length);
    out.put(s.lambda);
    put_vector(out, s.pos);
    put_vector(out, s.image);
    put_vector(out, s.vel);
    out.put(static_cast<uint8_t>(!s.externalForce.empty()));
    if (!s.externalForce.empty()) put_vector(out, s.externalForce);
    for (const std::vector<double>& state : s.integrators) {
        out.put(static_cast<uint32_t>(state.size()));
        put_vector(out, state);
    }
    // Last, each tagged and only when there are any: a checkpoint without them reads as before.
    if (!s.dir.empty()) {
        out.put(kOrientationsTag);
        put_vector(out, s.dir);
    }
    if (!s.magnetization.empty()) {
        out.put(kMagnetizationTag);
        put_vector(out, s.magnetization);
    }
    return out.bytes();
}

template <class R>
DynamicState<R> decode_state(const std::vector<unsigned char>& payload, const std::string& path, const StateShape& shape) {
    ByteReader in(payload, path);
    const auto mismatch = [&](const std::string& what) {
        return Error(STRUCTMD_ERR_IO, "checkpoint '" + path + "' does not fit this simulation: " + what);
    };
    const uint32_t realSize = in.get<uint32_t>();
    if (realSize != sizeof(R))
        throw mismatch(std::string("it was written in ") + (realSize == 4 ? "single" : "double") +
                       " precision, this simulation runs in " + shape.precision);
    const int64_t count = in.get<int64_t>();
    if (count != shape.particles)
        throw mismatch("it holds " + std::to_string(count) + " particles, this simulation " +
                       std::to_string(shape.particles));
    DynamicState<R> s;
    s.firstStep = in.get<int64_t>();
    if (s.firstStep != shape.firstStep)
        throw mismatch("its schedule starts at step " + std::to_string(s.firstStep) + ", this one at " +
                       std::to_string(shape.firstStep));
    s.step = in.get<int64_t>();
    s.time = in.get<double>();
    s.activeStage = in.get<int32_t>();
    for (double& length : s.box) length = in.get<double>();
    s.lambda = in.get<double>();
    if (s.step < shape.firstStep || s.step > shape.finalStep || s.activeStage < -1 || s.activeStage >= shape.stages ||
        !(s.lambda >= 0.0 && s.lambda <= 1.0))
        throw mismatch("its step, schedule stage or lambda is out of range");
    s.pos = get_vector<Real4<R>>(in, count);
    s.image = get_vector<Image>(in, count);
    s.vel = get_vector<Real4<R>>(in, count);
    if (in.get<uint8_t>()) s.externalForce = get_vector<Real4<R>>(in, count);
    s.integrators.resize(shape.integrators);
    for (auto& state : s.integrators) state = get_vector<double>(in, in.get<uint32_t>());
    while (!in.at_end()) {
        const uint8_t tag = in.get<uint8_t>();
        if (tag == kOrientationsTag && s.dir.empty() && s.magnetization.empty())
            s.dir = get_vector<Real4<R>>(in, count);
        else if (tag == kMagnetizationTag && s.magnetization.empty())
            s.magnetization = get_vector<Real4<R>>(in, count);
        else
            throw mismatch("it has more data than this simulation's integrators hold");
    }
    check_state_values(s, path, shape);
    return s;
}

template std::vector<unsigned char> encode_state<float>(const DynamicState<float>&);
template std::vector<unsigned char> encode_state<double>(const DynamicState<double>&);
template DynamicState<float> decode_state<float>(const std::vector<unsigned char>&, const std::string&, const StateShape&);
template DynamicState<double> decode_state<double>(const std::vector<unsigned char>&, const std::string&,
                                                   const StateShape&);

}  // namespace structmd
