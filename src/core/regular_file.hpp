#pragma once
// Reading a whole file the input names (the input itself, a table file, a checkpoint), refusing
// anything but a regular file: a directory cannot be read, and a device or a pipe (/dev/urandom,
// /dev/zero, a FIFO) may never end, so reading one would hang or grow until memory runs out. A
// regular file's size is known before it is read, which bounds the read.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

namespace structmd {

// The file's bytes, or, where it cannot be read, why not (empty when it could), to follow "<file>: ".
struct FileContents {
    std::string bytes;
    std::string problem;
};

inline FileContents read_regular_file(const std::string& path) {
    FileContents contents;
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        contents.problem = std::string("cannot open: ") + std::strerror(errno);
        return contents;
    }
    struct stat info {};
    if (::fstat(fd, &info) != 0 || !S_ISREG(info.st_mode)) {
        contents.problem = S_ISDIR(info.st_mode) ? "a directory, not a file"
                                                 : "not a regular file (a device, a pipe or a socket): reading it "
                                                   "might never end";
        ::close(fd);
        return contents;
    }
    contents.bytes.resize(static_cast<size_t>(info.st_size));
    size_t done = 0;
    while (done < contents.bytes.size()) {
        const ssize_t got = ::read(fd, &contents.bytes[done], contents.bytes.size() - done);
        if (got < 0 && errno == EINTR) continue;
        if (got <= 0) {
            contents.problem = got < 0 ? std::string("cannot read: ") + std::strerror(errno)
                                       : "shorter than its size while it was read";
            break;
        }
        done += static_cast<size_t>(got);
    }
    ::close(fd);
    return contents;
}

}  // namespace structmd
