#pragma once
// The trajectory formats of ["WriteStep","WriteStep"]. A writer appends one frame per call to its
// file, which it opens at the first frame (not at load, so a load that fails later leaves an old
// file alone): truncated, or kept and extended when appending.
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/error.hpp"

namespace structmd {

// One frame: the particles written (all, or a group's), in id order.
struct TrajectoryFrame {
    int64_t step = 0;
    double time = 0.0;
    std::array<double, 3> box{0, 0, 0};
    bool wrapped = true;                 // false: positions are unwrapped (images added back)
    std::vector<int64_t> ids;            // n, ascending
    std::vector<double> positions;       // 3n
    std::vector<int32_t> types;          // n rows of global.types, 0-based
    std::vector<double> radii;           // n
    std::vector<double> velocities;      // 3n for writers that need_velocities(), else empty
    std::vector<double> forces;          // 3n for writers that need_forces(), else empty
    std::vector<double> orientations;    // 4n quaternions [q0, q1, q2, q3] for writers that need_orientations()
    std::vector<double> moments;         // 3n magnetic moments (lab frame) for writers that need_moments()
    std::vector<std::string> typeNames;  // indexed by type
};

// What a format that describes molecules (PDB, and DCD's PSF topology) writes beside the positions,
// by particle id. Ids past the input's particles (a patchy entry's patches) have none of it.
struct MoleculeLayout {
    std::vector<int32_t> chain;    // structure's chainId; empty when not given
    std::vector<int32_t> residue;  // structure's resId; empty when not given
    std::vector<double> mass;      // the input's, by particle id
    std::vector<double> charge;    // the input's, by particle id
    std::vector<std::array<int64_t, 2>> bonds;      // the two-particle bonds, i < j, each pair once, sorted
    std::vector<std::array<int64_t, 3>> angles;     // the three-particle bonds, as listed (i, j, k), sorted
    std::vector<std::array<int64_t, 4>> dihedrals;  // the four-particle bonds, as listed, sorted
};

struct TrajectoryOptions {
    std::string path;        // the file written, extension included
    std::string owner;       // the entry's JSON path, which starts every message
    bool append = false;
    int64_t interval = 1;    // steps between frames (DCD NSAVC)
    double timeStep = 0.0;   // DCD DELTA; 0 when unknown
    MoleculeLayout molecules;  // filled for PDB and DCD only
};

class TrajectoryWriter {
public:
    virtual ~TrajectoryWriter() = default;
    // Throws Error(ERR_IO) naming the file and the reason when it cannot be opened or written.
    virtual void write(const TrajectoryFrame& frame) = 0;
    // What a frame must carry besides positions, types and radii: fetched only for those formats.
    virtual bool needs_velocities() const { return false; }
    virtual bool needs_forces() const { return false; }
    virtual bool needs_orientations() const { return false; }
    virtual bool needs_moments() const { return false; }
};

// The names outputFormat accepts, which are also the file extensions.
const std::vector<std::string>& trajectory_formats();

// The writer of a format; nullptr when the format is unknown.
std::unique_ptr<TrajectoryWriter> make_trajectory_writer(const std::string& format, TrajectoryOptions options);

// "<owner>: cannot <action> '<path>': <reason>" as Error(ERR_IO).
Error trajectory_io_error(const TrajectoryOptions& options, const std::string& action, const std::string& reason);

}  // namespace structmd
