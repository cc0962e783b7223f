#pragma once
// The checkpoint file: a magic string, a format version, the payload's length, the payload and an
// FNV-1a checksum of everything before it. Writing goes to a temporary file that is flushed and
// then renamed over the target, so a crash never leaves a half-written file in place of a good one.
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "core/error.hpp"

namespace structmd {

constexpr uint32_t kCheckpointFormatVersion = 2;  // 2: the ensemble's lambda after the box

// Throws Error(STRUCTMD_ERR_IO) naming the path and the reason.
void write_checkpoint_file(const std::string& path, const std::vector<unsigned char>& payload);
// Returns the payload; throws Error(STRUCTMD_ERR_IO) for a missing, truncated, corrupt or foreign file.
std::vector<unsigned char> read_checkpoint_file(const std::string& path);

class ByteWriter {
public:
    template <class T>
    void put(const T& value) {
        put_bytes(&value, sizeof(T));
    }
    void put_bytes(const void* data, size_t size) {
        const auto* bytes = static_cast<const unsigned char*>(data);
        bytes_.insert(bytes_.end(), bytes, bytes + size);
    }
    const std::vector<unsigned char>& bytes() const { return bytes_; }

private:
    std::vector<unsigned char> bytes_;
};

class ByteReader {
public:
    ByteReader(const std::vector<unsigned char>& bytes, std::string path) : bytes_(bytes), path_(std::move(path)) {}
    template <class T>
    T get() {
        T value;
        get_bytes(&value, sizeof(T));
        return value;
    }
    void get_bytes(void* data, size_t size) {
        if (size > bytes_.size() - offset_)
            throw Error(STRUCTMD_ERR_IO, "checkpoint '" + path_ + "': the payload ends early");
        if (size == 0) return;  // data may be null then (an empty vector's), which memcpy forbids
        std::memcpy(data, bytes_.data() + offset_, size);
        offset_ += size;
    }
    bool at_end() const { return offset_ == bytes_.size(); }
    size_t remaining() const { return bytes_.size() - offset_; }
    const std::string& path() const { return path_; }

private:
    const std::vector<unsigned char>& bytes_;
    std::string path_;
    size_t offset_ = 0;
};

}  // namespace structmd
