#pragma once
// A text trajectory format described as data: what starts a frame, and the lines written for each
// particle as a list of columns. TextFormatWriter writes any format so described, so a format's
// columns are stated once, in the table of trajectory_formats.cpp.
#include <cstdint>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "core/vec.hpp"
#include "steps/text_trajectory_writer.hpp"

namespace structmd {

// Particle k of a frame, as the columns read it.
class WrittenParticle {
public:
    WrittenParticle(const TrajectoryFrame& frame, const std::vector<int>& atomicNumbers, size_t k)
        : frame_(frame), atomicNumbers_(atomicNumbers), k_(k) {}

    int64_t id() const { return frame_.ids[k_]; }
    int32_t type() const { return frame_.types[k_]; }
    const std::string& type_name() const { return frame_.typeNames[type()]; }
    // The type name's atomic number when it is an element symbol, else 0.
    int atomic_number() const { return atomicNumbers_[type()]; }
    double radius() const { return frame_.radii[k_]; }
    Vec3<double> position() const { return triple(frame_.positions); }
    Vec3<double> velocity() const { return triple(frame_.velocities); }
    Vec3<double> force() const { return triple(frame_.forces); }
    Vec3<double> moment() const { return triple(frame_.moments); }
    // The moment's unit direction; zero for a moment of magnitude 0.
    Vec3<double> moment_direction() const;
    const double* quaternion() const { return &frame_.orientations[4 * k_]; }  // q0, q1, q2, q3
    // Body axis 0, 1 or 2 (x, y, z) in the lab frame.
    Vec3<double> body_axis(int axis) const;

private:
    Vec3<double> triple(const std::vector<double>& values) const {
        return {values[3 * k_], values[3 * k_ + 1], values[3 * k_ + 2]};
    }

    const TrajectoryFrame& frame_;
    const std::vector<int>& atomicNumbers_;
    size_t k_;
};

// One line of output: values separated by one space, integers as integers, reals with 8
// significant digits.
class LinePrinter {
public:
    explicit LinePrinter(std::FILE* file) : file_(file) {}
    void integer(int64_t value);
    void real(double value);
    void reals(const Vec3<double>& values);
    void text(const std::string& value);
    void end();

private:
    const char* separator();

    std::FILE* file_;
    bool first_ = true;
};

// A column: one or more adjacent values of a line.
using Column = std::function<void(const WrittenParticle&, LinePrinter&)>;
using TextLine = std::vector<Column>;

// What a frame must carry besides positions, types and radii for a format's columns.
enum FrameData : unsigned { kVelocities = 1u, kForces = 2u, kOrientations = 4u, kMoments = 8u };

// Writes what starts a frame.
using FrameStart = void (*)(std::FILE*, const TrajectoryFrame&);

struct TextFormat {
    FrameStart startFrame = nullptr;  // null: frames follow one another with no header
    std::vector<TextLine> lines;      // written for each particle, in this order
    unsigned needs = 0;               // FrameData
    std::string fileHeader;           // once at the top of a file that is not appended to
};

class TextFormatWriter final : public TextTrajectoryWriter {
public:
    TextFormatWriter(TrajectoryOptions options, TextFormat format)
        : TextTrajectoryWriter(std::move(options)), format_(std::move(format)) {}
    bool needs_velocities() const override { return format_.needs & kVelocities; }
    bool needs_forces() const override { return format_.needs & kForces; }
    bool needs_orientations() const override { return format_.needs & kOrientations; }
    bool needs_moments() const override { return format_.needs & kMoments; }

protected:
    void write_frame(std::FILE* f, const TrajectoryFrame& frame) override;

private:
    TextFormat format_;
    std::vector<int> atomicNumbers_;  // by type
};

}  // namespace structmd
