#include "steps/measure_file.hpp"

#include <cerrno>
#include <cstring>

#include "core/error.hpp"

namespace structmd {

MeasureFile::MeasureFile(std::string owner, std::string path, std::string header)
    : owner_(std::move(owner)), path_(std::move(path)), header_(std::move(header)), file_(nullptr, &std::fclose) {}

std::FILE* MeasureFile::stream() {
    if (!file_) {
        file_.reset(std::fopen(path_.c_str(), "w"));
        if (!file_)
            throw Error(STRUCTMD_ERR_IO,
                        owner_ + ": cannot open '" + path_ + "' for writing: " + std::strerror(errno));
        if (!header_.empty()) std::fprintf(file_.get(), "%s\n", header_.c_str());
    }
    return file_.get();
}

void MeasureFile::flush() {
    if (file_ && (std::fflush(file_.get()) != 0 || std::ferror(file_.get())))
        throw Error(STRUCTMD_ERR_IO, owner_ + ": cannot write '" + path_ + "': " + std::strerror(errno));
}

}  // namespace structmd
