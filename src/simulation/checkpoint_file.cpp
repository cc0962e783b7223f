#include "simulation/checkpoint_file.hpp"

#include <cerrno>
#include <cstdio>

#include <unistd.h>

#include "core/regular_file.hpp"

namespace structmd {

namespace {

const char kMagic[8] = {'S', 'T', 'R', 'U', 'C', 'T', 'M', 'D'};

uint64_t fnv1a(const unsigned char* data, size_t size) {
    uint64_t hash = 1469598103934665603ull;
    for (size_t k = 0; k < size; ++k) {
        hash ^= data[k];
        hash *= 1099511628211ull;
    }
    return hash;
}

Error io_error(const std::string& path, const std::string& what) {
    return Error(STRUCTMD_ERR_IO, "checkpoint '" + path + "': " + what);
}

}  // namespace

void write_checkpoint_file(const std::string& path, const std::vector<unsigned char>& payload) {
    ByteWriter file;
    file.put_bytes(kMagic, sizeof(kMagic));
    file.put(kCheckpointFormatVersion);
    file.put(static_cast<uint64_t>(payload.size()));
    file.put_bytes(payload.data(), payload.size());
    file.put(fnv1a(file.bytes().data(), file.bytes().size()));

    const std::string temporary = path + ".tmp";
    std::FILE* out = std::fopen(temporary.c_str(), "wb");
    if (!out) throw io_error(path, std::string("cannot create '") + temporary + "': " + std::strerror(errno));
    const bool written = std::fwrite(file.bytes().data(), 1, file.bytes().size(), out) == file.bytes().size() &&
                         std::fflush(out) == 0 && fsync(fileno(out)) == 0;
    const int writeError = errno;
    if (std::fclose(out) != 0 || !written) {
        std::remove(temporary.c_str());
        throw io_error(path, std::string("cannot write: ") + std::strerror(writeError));
    }
    if (std::rename(temporary.c_str(), path.c_str()) != 0) {
        const int renameError = errno;
        std::remove(temporary.c_str());
        throw io_error(path, std::string("cannot replace the file: ") + std::strerror(renameError));
    }
}

std::vector<unsigned char> read_checkpoint_file(const std::string& path) {
    const FileContents file = read_regular_file(path);
    if (!file.problem.empty()) throw io_error(path, file.problem);
    const std::vector<unsigned char> bytes(file.bytes.begin(), file.bytes.end());
    const size_t header = sizeof(kMagic) + sizeof(uint32_t) + sizeof(uint64_t);
    if (bytes.size() < header || std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0)
        throw io_error(path, "not a structmd checkpoint");
    uint32_t version = 0;
    uint64_t length = 0;
    std::memcpy(&version, bytes.data() + sizeof(kMagic), sizeof(version));
    std::memcpy(&length, bytes.data() + sizeof(kMagic) + sizeof(version), sizeof(length));
    if (version != kCheckpointFormatVersion)
        throw io_error(path, "format version " + std::to_string(version) + ", this build reads version " +
                                 std::to_string(kCheckpointFormatVersion));
    if (bytes.size() != header + length + sizeof(uint64_t))
        throw io_error(path, "the file is truncated or has trailing bytes (" + std::to_string(bytes.size()) +
                                 " bytes, expected " + std::to_string(header + length + sizeof(uint64_t)) + ")");
    uint64_t stored = 0;
    std::memcpy(&stored, bytes.data() + header + length, sizeof(stored));
    if (stored != fnv1a(bytes.data(), header + length)) throw io_error(path, "checksum mismatch: the file is corrupt");
    return std::vector<unsigned char>(bytes.begin() + header, bytes.begin() + header + length);
}

}  // namespace structmd
