#pragma once
// What every text trajectory format shares: the file opened at the first frame, flushed after every
// frame so the file is complete whenever the host looks at it, and stream failures as ERR_IO.
#include <cstdint>
#include <cstdio>
#include <memory>

#include "steps/trajectory_writer.hpp"

namespace structmd {

class TextTrajectoryWriter : public TrajectoryWriter {
public:
    explicit TextTrajectoryWriter(TrajectoryOptions options);
    void write(const TrajectoryFrame& frame) final;

protected:
    virtual void write_frame(std::FILE* f, const TrajectoryFrame& frame) = 0;
    // Formats that number their frames count those already in a file they append to.
    virtual void count_existing_frames() {}
    int64_t frames() const { return frames_; }
    void set_frames(int64_t frames) { frames_ = frames; }
    const TrajectoryOptions& options() const { return options_; }

private:
    TrajectoryOptions options_;
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> file_;
    int64_t frames_ = 0;  // frames in the file before the one being written
};

}  // namespace structmd
