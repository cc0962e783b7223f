#pragma once
// The CHARMM/NAMD DCD trajectory, as written here. Little-endian whatever the host; every record is
// framed by its length in bytes as an int32 before and after it, as Fortran unformatted I/O does.
//
//   header record (84 bytes): "CORD", then 20 int32 control words, 0 unless listed:
//     [0]  NSET    frames in the file, rewritten after every frame
//     [1]  ISTART  step of the first frame
//     [2]  NSAVC   steps between frames (the entry's intervalStep)
//     [3]  NSTEP   steps from the first frame to the last, rewritten after every frame
//     [8]  NAMNF   fixed atoms: 0
//     [9]  DELTA   the time step as a float32, in the simulation's time unit (CHARMM readers take
//                  it as AKMA units of 48.88821 fs); 0 when unknown
//     [10]         1: every frame has a unit-cell record
//     [19]         24, the CHARMM version whose layout this is
//   title record: int32 NTITLE = 2, then NTITLE lines of 80 characters
//   atom record: int32 N
//   per frame: the unit-cell record, 6 float64 in NAMD's order A, gamma, B, beta, alpha, C (box
//     lengths; angles in degrees, 90), then three records of N float32: every x, every y, every z.
//
// Byte offsets: control word k at 8 + 4k; the header, title and atom records take 276 bytes; a frame
// takes 80 + 12 N. Appending extends a file of this layout with the same N and keeps its ISTART,
// NSAVC and DELTA. The final state of a run may fall between intervals; its frame is written anyway.
//
// Beside it, when its first frame is written, the particles' topology as a PSF file of the same name
// (psf_topology.hpp), so that MDAnalysis and VMD load the pair directly.
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "steps/trajectory_writer.hpp"

namespace structmd {

class DcdWriter final : public TrajectoryWriter {
public:
    explicit DcdWriter(TrajectoryOptions options);
    void write(const TrajectoryFrame& frame) override;
    // "<path less its extension>.psf".
    static std::string topology_path(const std::string& dcdPath);

private:
    void create(const TrajectoryFrame& first);
    // Opens the file to extend; false when there is none (or it is empty), so a new one is made.
    bool open_existing(int64_t particles);
    void write_bytes(const std::vector<unsigned char>& bytes);
    void write_int32_at(long offset, int32_t value);
    int32_t to_int32(int64_t value, const char* what) const;

    TrajectoryOptions options_;
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> file_;
    int32_t frames_ = 0;
    int64_t firstStep_ = 0;
    std::vector<unsigned char> buffer_;
};

}  // namespace structmd
