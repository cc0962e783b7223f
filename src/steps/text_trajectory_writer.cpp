#include "steps/text_trajectory_writer.hpp"

#include <cerrno>
#include <cstring>

namespace structmd {

TextTrajectoryWriter::TextTrajectoryWriter(TrajectoryOptions options)
    : options_(std::move(options)), file_(nullptr, &std::fclose) {}

void TextTrajectoryWriter::write(const TrajectoryFrame& frame) {
    if (!file_) {
        if (options_.append) count_existing_frames();
        file_.reset(std::fopen(options_.path.c_str(), options_.append ? "a" : "w"));
        if (!file_) throw trajectory_io_error(options_, "open", std::strerror(errno));
    }
    errno = 0;
    write_frame(file_.get(), frame);
    ++frames_;
    if (std::fflush(file_.get()) != 0 || std::ferror(file_.get()))
        throw trajectory_io_error(options_, "write", errno ? std::strerror(errno) : "stream error");
}

}  // namespace structmd
