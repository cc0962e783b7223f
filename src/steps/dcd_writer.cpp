#include "steps/dcd_writer.hpp"

#include <cerrno>
#include <cstring>
#include <limits>

#include "steps/psf_topology.hpp"

namespace structmd {

namespace {

constexpr int32_t kHeaderRecordBytes = 84;  // "CORD" + 20 control words
constexpr long kControlOffset = 8;          // after the record marker and "CORD"
constexpr int kNset = 0, kIstart = 1, kNsavc = 2, kNstep = 3, kFixedAtoms = 8, kDelta = 9, kHasUnitCell = 10,
              kFourDimensions = 11, kCharmmVersion = 19;
constexpr int32_t kTitleLines = 2;
constexpr size_t kTitleLength = 80;
constexpr int32_t kUnitCellBytes = 6 * 8;
constexpr double kRightAngle = 90.0;

void put_u32(std::vector<unsigned char>& out, uint32_t value) {
    for (int byte = 0; byte < 4; ++byte) out.push_back(static_cast<unsigned char>(value >> (8 * byte)));
}
void put_i32(std::vector<unsigned char>& out, int32_t value) { put_u32(out, static_cast<uint32_t>(value)); }
void put_f32(std::vector<unsigned char>& out, float value) {
    uint32_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    put_u32(out, bits);
}
void put_f64(std::vector<unsigned char>& out, double value) {
    uint64_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    for (int byte = 0; byte < 8; ++byte) out.push_back(static_cast<unsigned char>(bits >> (8 * byte)));
}
int32_t get_i32(const unsigned char* bytes) {
    uint32_t value = 0;
    for (int byte = 0; byte < 4; ++byte) value |= static_cast<uint32_t>(bytes[byte]) << (8 * byte);
    return static_cast<int32_t>(value);
}

void put_title(std::vector<unsigned char>& out, std::string line) {
    line.resize(kTitleLength, ' ');
    out.insert(out.end(), line.begin(), line.end());
}

int64_t frame_bytes(int64_t particles) { return 4 + kUnitCellBytes + 4 + 3 * (4 + 4 * particles + 4); }

}  // namespace

std::string DcdWriter::topology_path(const std::string& dcdPath) {
    const size_t dot = dcdPath.rfind('.');
    const size_t slash = dcdPath.find_last_of('/');
    const bool hasExtension = dot != std::string::npos && (slash == std::string::npos || dot > slash);
    return (hasExtension ? dcdPath.substr(0, dot) : dcdPath) + ".psf";
}

DcdWriter::DcdWriter(TrajectoryOptions options) : options_(std::move(options)), file_(nullptr, &std::fclose) {}

int32_t DcdWriter::to_int32(int64_t value, const char* what) const {
    if (value < std::numeric_limits<int32_t>::min() || value > std::numeric_limits<int32_t>::max())
        throw Error(STRUCTMD_ERR_UNSUPPORTED, options_.owner + ": DCD stores " + what + " as a 32-bit integer; " +
                                                  std::to_string(value) + " does not fit ('" + options_.path + "')");
    return static_cast<int32_t>(value);
}

void DcdWriter::write_bytes(const std::vector<unsigned char>& bytes) {
    errno = 0;
    if (std::fwrite(bytes.data(), 1, bytes.size(), file_.get()) != bytes.size())
        throw trajectory_io_error(options_, "write", errno ? std::strerror(errno) : "short write");
}

void DcdWriter::write_int32_at(long offset, int32_t value) {
    std::vector<unsigned char> bytes;
    put_i32(bytes, value);
    if (std::fseek(file_.get(), offset, SEEK_SET) != 0)
        throw trajectory_io_error(options_, "seek in", std::strerror(errno));
    write_bytes(bytes);
}

void DcdWriter::create(const TrajectoryFrame& first) {
    file_.reset(std::fopen(options_.path.c_str(), "wb"));
    if (!file_) throw trajectory_io_error(options_, "open", std::strerror(errno));
    const int64_t n = static_cast<int64_t>(first.types.size());
    firstStep_ = first.step;
    frames_ = 0;

    std::vector<int32_t> control(20, 0);
    control[kIstart] = to_int32(first.step, "the first step (ISTART)");
    control[kNsavc] = to_int32(options_.interval, "the interval (NSAVC)");
    const float delta = static_cast<float>(options_.timeStep);
    std::memcpy(&control[kDelta], &delta, sizeof delta);
    control[kHasUnitCell] = 1;
    control[kCharmmVersion] = 24;

    std::vector<unsigned char> header;
    put_i32(header, kHeaderRecordBytes);
    header.insert(header.end(), {'C', 'O', 'R', 'D'});
    for (int32_t word : control) put_i32(header, word);
    put_i32(header, kHeaderRecordBytes);

    const int32_t titleBytes = 4 + kTitleLines * static_cast<int32_t>(kTitleLength);
    put_i32(header, titleBytes);
    put_i32(header, kTitleLines);
    put_title(header, "REMARKS written by structmd " STRUCTMD_VERSION_STRING);
    put_title(header, "REMARKS " + options_.owner);
    put_i32(header, titleBytes);

    put_i32(header, 4);
    put_i32(header, to_int32(n, "the number of particles"));
    put_i32(header, 4);
    write_bytes(header);
}

bool DcdWriter::open_existing(int64_t particles) {
    file_.reset(std::fopen(options_.path.c_str(), "r+b"));
    if (!file_) {
        if (errno == ENOENT) return false;
        throw trajectory_io_error(options_, "open", std::strerror(errno));
    }
    const auto unusable = [&](const std::string& why) {
        return trajectory_io_error(options_, "append to", why);
    };
    unsigned char header[4 + kHeaderRecordBytes + 4];
    const size_t got = std::fread(header, 1, sizeof header, file_.get());
    if (got == 0 && std::feof(file_.get())) return false;
    if (got != sizeof header || get_i32(header) != kHeaderRecordBytes || std::memcmp(header + 4, "CORD", 4) != 0 ||
        get_i32(header + 4 + kHeaderRecordBytes) != kHeaderRecordBytes)
        throw unusable("not a little-endian CHARMM/NAMD DCD file");
    const auto control = [&](int word) { return get_i32(header + kControlOffset + 4 * word); };
    if (control(kHasUnitCell) != 1 || control(kFixedAtoms) != 0 || control(kFourDimensions) != 0)
        throw unusable("its frames have another layout (this writer needs unit cells, no fixed atoms, 3 dimensions)");

    unsigned char marker[4];
    if (std::fread(marker, 1, 4, file_.get()) != 4) throw unusable("the title record is missing");
    const int32_t titleBytes = get_i32(marker);
    if (titleBytes < 4 || std::fseek(file_.get(), titleBytes, SEEK_CUR) != 0 ||
        std::fread(marker, 1, 4, file_.get()) != 4 || get_i32(marker) != titleBytes)
        throw unusable("the title record is damaged");
    unsigned char atoms[12];
    if (std::fread(atoms, 1, sizeof atoms, file_.get()) != sizeof atoms || get_i32(atoms) != 4 ||
        get_i32(atoms + 8) != 4)
        throw unusable("the atom-count record is damaged");
    if (get_i32(atoms + 4) != particles)
        throw unusable("it holds " + std::to_string(get_i32(atoms + 4)) + " particles, the simulation " +
                       std::to_string(particles));

    const int64_t headerBytes = static_cast<int64_t>(sizeof header) + 4 + titleBytes + 4 + sizeof atoms;
    const int64_t expected = headerBytes + static_cast<int64_t>(control(kNset)) * frame_bytes(particles);
    if (std::fseek(file_.get(), 0, SEEK_END) != 0) throw trajectory_io_error(options_, "seek in", std::strerror(errno));
    const long size = std::ftell(file_.get());
    if (control(kNset) < 0 || size != expected)
        throw unusable("its size (" + std::to_string(size) + " bytes) does not match its header (" +
                       std::to_string(control(kNset)) + " frames of " + std::to_string(frame_bytes(particles)) +
                       " bytes after " + std::to_string(headerBytes) + " bytes)");
    frames_ = control(kNset);
    firstStep_ = control(kIstart);
    return true;
}

void DcdWriter::write(const TrajectoryFrame& frame) {
    const int64_t n = static_cast<int64_t>(frame.types.size());
    if (!file_) {
        to_int32(4 * n, "a coordinate record's length (4 N)");
        if (!(options_.append && open_existing(n))) create(frame);
        write_psf_topology(topology_path(options_.path), options_.owner, frame, options_.molecules);
    }
    if (frames_ == std::numeric_limits<int32_t>::max()) to_int32(int64_t{frames_} + 1, "the frame count (NSET)");

    buffer_.clear();
    put_i32(buffer_, kUnitCellBytes);
    for (double value : {frame.box[0], kRightAngle, frame.box[1], kRightAngle, kRightAngle, frame.box[2]})
        put_f64(buffer_, value);
    put_i32(buffer_, kUnitCellBytes);
    for (int axis = 0; axis < 3; ++axis) {
        put_i32(buffer_, static_cast<int32_t>(4 * n));
        for (int64_t i = 0; i < n; ++i) put_f32(buffer_, static_cast<float>(frame.positions[3 * i + axis]));
        put_i32(buffer_, static_cast<int32_t>(4 * n));
    }
    write_bytes(buffer_);

    // The header promises only complete frames: it is updated after the frame is written.
    ++frames_;
    write_int32_at(kControlOffset + 4 * kNset, frames_);
    write_int32_at(kControlOffset + 4 * kNstep, to_int32(frame.step - firstStep_, "the steps covered (NSTEP)"));
    if (std::fseek(file_.get(), 0, SEEK_END) != 0) throw trajectory_io_error(options_, "seek in", std::strerror(errno));
    if (std::fflush(file_.get()) != 0) throw trajectory_io_error(options_, "write", std::strerror(errno));
}

}  // namespace structmd
