// The text trajectory formats (xyz, sp, spf, lammpstrj, pdb, and UAMMD-structured's coord, vel,
// itpv, the orientation formats spo, svv and itpd and the magnetic ones magnet, xyzm, spm, svvm and
// svvma) and the table of every format. Values are written with 8 significant digits (pdb: its fixed
// columns).
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <vector>

#include "core/quaternion.hpp"
#include "steps/chemical_elements.hpp"
#include "steps/dcd_writer.hpp"
#include "steps/trajectory_writer.hpp"

namespace structmd {

Error trajectory_io_error(const TrajectoryOptions& options, const std::string& action, const std::string& reason) {
    return Error(STRUCTMD_ERR_IO, options.owner + ": cannot " + action + " '" + options.path + "': " + reason);
}

namespace {

// Opens the file at the first frame, flushes after every frame so the file is complete whenever
// the host looks at it, and turns stream failures into ERR_IO.
class TextTrajectoryWriter : public TrajectoryWriter {
public:
    explicit TextTrajectoryWriter(TrajectoryOptions options)
        : options_(std::move(options)), file_(nullptr, &std::fclose) {}

    void write(const TrajectoryFrame& frame) final {
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

// N, a comment line in the extended-XYZ style (step, time, box), then "type x y z Z t" per
// particle: the type's name, the atomic number when the name is an element (else 0, which ASE
// reads as a dummy atom instead of failing on a coarse-grained name) and the type's row.
class XyzWriter final : public TextTrajectoryWriter {
public:
    using TextTrajectoryWriter::TextTrajectoryWriter;

protected:
    void write_frame(std::FILE* f, const TrajectoryFrame& frame) override {
        if (numbers_.size() != frame.typeNames.size()) {
            numbers_.clear();
            for (const std::string& name : frame.typeNames) numbers_.push_back(atomic_number(name));
        }
        const size_t n = frame.types.size();
        const auto& L = frame.box;
        std::fprintf(f,
                     "%zu\nstep=%lld time=%.8g Lattice=\"%.8g 0 0 0 %.8g 0 0 0 %.8g\" "
                     "Properties=species:S:1:pos:R:3:Z:I:1:type:I:1 pbc=\"T T T\"\n",
                     n, static_cast<long long>(frame.step), frame.time, L[0], L[1], L[2]);
        for (size_t i = 0; i < n; ++i) {
            const int32_t type = frame.types[i];
            std::fprintf(f, "%s %.8g %.8g %.8g %d %d\n", frame.typeNames[type].c_str(), frame.positions[3 * i],
                         frame.positions[3 * i + 1], frame.positions[3 * i + 2], numbers_[type], type);
        }
    }

private:
    std::vector<int> numbers_;  // atomic number by type
};

// The superpunto frame header: the half box lengths.
void write_sp_header(std::FILE* f, const TrajectoryFrame& frame) {
    const auto& L = frame.box;
    std::fprintf(f, "#Lx=%.8g;Ly=%.8g;Lz=%.8g;\n", 0.5 * L[0], 0.5 * L[1], 0.5 * L[2]);
}

Vec3<double> position_of(const TrajectoryFrame& frame, size_t k) {
    return {frame.positions[3 * k], frame.positions[3 * k + 1], frame.positions[3 * k + 2]};
}

// One sphere of the superpunto family: "x y z radius type".
void write_sphere(std::FILE* f, const Vec3<double>& p, double radius, int type) {
    std::fprintf(f, "%.8g %.8g %.8g %.8g %d\n", p.x, p.y, p.z, radius, type);
}

// The superpunto format: a header with the half box lengths, then "x y z radius type" per particle.
class SpWriter final : public TextTrajectoryWriter {
public:
    using TextTrajectoryWriter::TextTrajectoryWriter;

protected:
    void write_frame(std::FILE* f, const TrajectoryFrame& frame) override {
        write_sp_header(f, frame);
        for (size_t i = 0; i < frame.types.size(); ++i)
            write_sphere(f, position_of(frame, i), frame.radii[i], frame.types[i]);
    }
};

// sp with each particle's force: "x y z radius type fx fy fz".
class SpfWriter final : public TextTrajectoryWriter {
public:
    using TextTrajectoryWriter::TextTrajectoryWriter;
    bool needs_forces() const override { return true; }

protected:
    void write_frame(std::FILE* f, const TrajectoryFrame& frame) override {
        write_sp_header(f, frame);
        const double* r = frame.positions.data();
        const double* F = frame.forces.data();
        for (size_t i = 0; i < frame.types.size(); ++i)
            std::fprintf(f, "%.8g %.8g %.8g %.8g %d %.8g %.8g %.8g\n", r[3 * i], r[3 * i + 1], r[3 * i + 2],
                         frame.radii[i], frame.types[i], F[3 * i], F[3 * i + 1], F[3 * i + 2]);
    }
};

// The body frame's axes of particle k of a frame, in the lab frame.
struct BodyAxes {
    Vec3<double> x, y, z;
};
BodyAxes body_axes(const TrajectoryFrame& frame, size_t k) {
    const double* q = &frame.orientations[4 * k];
    const Real4<double> quaternion{q[0], q[1], q[2], q[3]};
    return {body_x(quaternion), body_y(quaternion), body_z(quaternion)};
}

// UAMMD-structured's spo (superpunto with orientations): per particle the sp line "x y z radius type",
// then three small spheres (radius / 5) on its surface along its body axes, "x+a y+a z+a radius/5 t"
// with a the x, y, z body axis times the radius and t = 2, 3, 4 times the type.
class SpoWriter final : public TextTrajectoryWriter {
public:
    using TextTrajectoryWriter::TextTrajectoryWriter;
    bool needs_orientations() const override { return true; }

protected:
    void write_frame(std::FILE* f, const TrajectoryFrame& frame) override {
        write_sp_header(f, frame);
        for (size_t i = 0; i < frame.types.size(); ++i) {
            const Vec3<double> p = position_of(frame, i);
            const double a = frame.radii[i];
            const int type = frame.types[i];
            write_sphere(f, p, a, type);
            const BodyAxes axes = body_axes(frame, i);
            const Vec3<double> marked[3] = {axes.x, axes.y, axes.z};
            for (int k = 0; k < 3; ++k) {
                const Vec3<double> m = p + a * marked[k];
                write_sphere(f, m, 0.2 * a, (k + 2) * type);
            }
        }
    }
};

// UAMMD-structured's svv (superpunto with arrows, for SVV3D): per particle the sp line
// "x y z radius type", then its three body axes as arrows "x y z ax ay az color" of length twice the
// radius, colored 1 (x), 5 (y) and 8 (z).
class SvvWriter final : public TextTrajectoryWriter {
public:
    using TextTrajectoryWriter::TextTrajectoryWriter;
    bool needs_orientations() const override { return true; }

protected:
    void write_frame(std::FILE* f, const TrajectoryFrame& frame) override {
        write_sp_header(f, frame);
        static constexpr int kColors[3] = {1, 5, 8};
        for (size_t i = 0; i < frame.types.size(); ++i) {
            const Vec3<double> p = position_of(frame, i);
            const double a = frame.radii[i];
            write_sphere(f, p, a, frame.types[i]);
            const BodyAxes axes = body_axes(frame, i);
            const Vec3<double> arrows[3] = {axes.x, axes.y, axes.z};
            for (int k = 0; k < 3; ++k) {
                const Vec3<double> v = (2.0 * a) * arrows[k];
                std::fprintf(f, "%.8g %.8g %.8g %.8g %.8g %.8g %d\n", p.x, p.y, p.z, v.x, v.y, v.z, kColors[k]);
            }
        }
    }
};

// UAMMD-structured's itpd: N, an empty line, then "id type x y z q0 q1 q2 q3" per particle.
class ItpdWriter final : public TextTrajectoryWriter {
public:
    using TextTrajectoryWriter::TextTrajectoryWriter;
    bool needs_orientations() const override { return true; }

protected:
    void write_frame(std::FILE* f, const TrajectoryFrame& frame) override {
        const double* r = frame.positions.data();
        const double* q = frame.orientations.data();
        std::fprintf(f, "%zu\n\n", frame.ids.size());
        for (size_t i = 0; i < frame.ids.size(); ++i)
            std::fprintf(f, "%lld %d %.8g %.8g %.8g %.8g %.8g %.8g %.8g\n", static_cast<long long>(frame.ids[i]),
                         frame.types[i], r[3 * i], r[3 * i + 1], r[3 * i + 2], q[4 * i], q[4 * i + 1], q[4 * i + 2],
                         q[4 * i + 3]);
    }
};

// UAMMD-structured's coord: "id x y z vx vy vz" per particle, frames one after the other with no
// line between them (each frame has as many lines as particles written).
class CoordWriter final : public TextTrajectoryWriter {
public:
    using TextTrajectoryWriter::TextTrajectoryWriter;
    bool needs_velocities() const override { return true; }

protected:
    void write_frame(std::FILE* f, const TrajectoryFrame& frame) override {
        const double* r = frame.positions.data();
        const double* v = frame.velocities.data();
        for (size_t i = 0; i < frame.ids.size(); ++i)
            std::fprintf(f, "%lld %.8g %.8g %.8g %.8g %.8g %.8g\n", static_cast<long long>(frame.ids[i]), r[3 * i],
                         r[3 * i + 1], r[3 * i + 2], v[3 * i], v[3 * i + 1], v[3 * i + 2]);
    }
};

// UAMMD-structured's vel: "vx vy vz |v|" per particle, frames one after the other.
class VelocityWriter final : public TextTrajectoryWriter {
public:
    using TextTrajectoryWriter::TextTrajectoryWriter;
    bool needs_velocities() const override { return true; }

protected:
    void write_frame(std::FILE* f, const TrajectoryFrame& frame) override {
        const double* v = frame.velocities.data();
        for (size_t i = 0; i < frame.ids.size(); ++i) {
            const double x = v[3 * i], y = v[3 * i + 1], z = v[3 * i + 2];
            std::fprintf(f, "%.8g %.8g %.8g %.8g\n", x, y, z, std::sqrt(x * x + y * y + z * z));
        }
    }
};

// UAMMD-structured's itpv: N, an empty line, then "id type x y z vx vy vz" per particle.
class ItpvWriter final : public TextTrajectoryWriter {
public:
    using TextTrajectoryWriter::TextTrajectoryWriter;
    bool needs_velocities() const override { return true; }

protected:
    void write_frame(std::FILE* f, const TrajectoryFrame& frame) override {
        const double* r = frame.positions.data();
        const double* v = frame.velocities.data();
        std::fprintf(f, "%zu\n\n", frame.ids.size());
        for (size_t i = 0; i < frame.ids.size(); ++i)
            std::fprintf(f, "%lld %d %.8g %.8g %.8g %.8g %.8g %.8g\n", static_cast<long long>(frame.ids[i]),
                         frame.types[i], r[3 * i], r[3 * i + 1], r[3 * i + 2], v[3 * i], v[3 * i + 1], v[3 * i + 2]);
    }
};

// A LAMMPS text dump: ids and types from 1, as LAMMPS counts them; xu yu zu mark unwrapped positions.
class LammpsDumpWriter final : public TextTrajectoryWriter {
public:
    using TextTrajectoryWriter::TextTrajectoryWriter;

protected:
    void write_frame(std::FILE* f, const TrajectoryFrame& frame) override {
        const size_t n = frame.types.size();
        std::fprintf(f, "ITEM: TIMESTEP\n%lld\nITEM: NUMBER OF ATOMS\n%zu\nITEM: BOX BOUNDS pp pp pp\n",
                     static_cast<long long>(frame.step), n);
        for (double L : frame.box) std::fprintf(f, "%.8g %.8g\n", -0.5 * L, 0.5 * L);
        std::fprintf(f, frame.wrapped ? "ITEM: ATOMS id type x y z\n" : "ITEM: ATOMS id type xu yu zu\n");
        for (size_t i = 0; i < n; ++i)
            std::fprintf(f, "%lld %d %.8g %.8g %.8g\n", static_cast<long long>(frame.ids[i] + 1), frame.types[i] + 1,
                         frame.positions[3 * i],
                         frame.positions[3 * i + 1], frame.positions[3 * i + 2]);
    }
};

// PDB: MODEL, CRYST1, one ATOM record per particle, ENDMDL. No END record, so that frames can be
// appended. ATOM: serial id+1 modulo 100000, the type name as atom name, residue UNK numbered by the
// structure's resId (modulo 10000; 1 without it), chain letter by its chainId (kChainLetters
// cyclically; A without it), element the type name when it is one, else X (ASE's unknown element,
// which its reader needs for coarse-grained names). The fixed columns hold coordinates from -999.999
// to 9999.999; larger ones widen the line. The first model of a file carries CONECT records for the two-particle bonds
// among the particles written, the one place VMD, MDAnalysis and others read bonds from in a
// multi-model file, when serials are unambiguous (every id below 99999).
class PdbWriter final : public TextTrajectoryWriter {
public:
    using TextTrajectoryWriter::TextTrajectoryWriter;

protected:
    void count_existing_frames() override {
        std::unique_ptr<std::FILE, int (*)(std::FILE*)> existing(std::fopen(options().path.c_str(), "r"), &std::fclose);
        if (!existing) return;
        int64_t models = 0;
        char line[128];
        bool lineStart = true;
        while (std::fgets(line, sizeof line, existing.get())) {
            if (lineStart && std::strncmp(line, "MODEL ", 6) == 0) ++models;
            lineStart = std::strchr(line, '\n') != nullptr;
        }
        set_frames(models);
    }

    void write_frame(std::FILE* f, const TrajectoryFrame& frame) override {
        const auto& L = frame.box;
        const MoleculeLayout& molecules = options().molecules;
        std::fprintf(f, "MODEL     %4lld\n", static_cast<long long>(frames() + 1));
        std::fprintf(f, "CRYST1%9.3f%9.3f%9.3f%7.2f%7.2f%7.2f %-11s%4d\n", L[0], L[1], L[2], 90.0, 90.0, 90.0, "P 1", 1);
        for (size_t i = 0; i < frame.types.size(); ++i) {
            const auto id = static_cast<size_t>(frame.ids[i]);
            const char chain = molecules.chain.empty() ? 'A' : chain_letter(molecules.chain[id]);
            const int residue = molecules.residue.empty() ? 1 : wrapped_residue(molecules.residue[id]);
            const std::string& name = frame.typeNames[frame.types[i]];
            std::fprintf(f, "ATOM  %5d %-4.4s UNK %c%4d    %8.3f%8.3f%8.3f%6.2f%6.2f          %2s\n",
                         serial(frame.ids[i]), name.c_str(), chain, residue, frame.positions[3 * i],
                         frame.positions[3 * i + 1], frame.positions[3 * i + 2], 1.0, 0.0,
                         atomic_number(name) > 0 ? name.c_str() : "X");
        }
        if (frames() == 0) write_connections(f, frame);
        std::fprintf(f, "ENDMDL\n");
    }

private:
    static constexpr const char* kChainLetters = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789";
    static constexpr int64_t kSerials = 100000;

    static int serial(int64_t id) { return static_cast<int>((id + 1) % kSerials); }
    static char chain_letter(int32_t chain) {
        const auto count = static_cast<int32_t>(std::strlen(kChainLetters));
        return kChainLetters[((chain % count) + count) % count];
    }
    static int wrapped_residue(int32_t residue) { return ((residue % 10000) + 10000) % 10000; }

    // CONECT records: each particle with its bonded partners among those written, four per record.
    void write_connections(std::FILE* f, const TrajectoryFrame& frame) const {
        const std::vector<std::array<int64_t, 2>>& bonds = options().molecules.bonds;
        if (bonds.empty() || frame.ids.empty() || frame.ids.back() + 1 >= kSerials) return;
        auto written = [&](int64_t id) { return std::binary_search(frame.ids.begin(), frame.ids.end(), id); };
        std::map<int64_t, std::vector<int64_t>> partners;
        for (const auto& [i, j] : bonds) {
            if (!written(i) || !written(j)) continue;
            partners[i].push_back(j);
            partners[j].push_back(i);
        }
        for (auto& [id, others] : partners) {
            std::sort(others.begin(), others.end());
            for (size_t k = 0; k < others.size(); k += 4) {
                std::fprintf(f, "CONECT%5d", serial(id));
                for (size_t m = k; m < std::min(k + 4, others.size()); ++m) std::fprintf(f, "%5d", serial(others[m]));
                std::fprintf(f, "\n");
            }
        }
    }
};


// The magnetic formats. The moment of particle k of a frame (lab frame), and its unit direction (zero
// for a moment of magnitude 0).
Vec3<double> moment_of(const TrajectoryFrame& frame, size_t k) {
    return {frame.moments[3 * k], frame.moments[3 * k + 1], frame.moments[3 * k + 2]};
}
Vec3<double> moment_direction(const TrajectoryFrame& frame, size_t k) {
    const Vec3<double> mu = moment_of(frame, k);
    const double norm = std::sqrt(dot(mu, mu));
    return norm > 0.0 ? (1.0 / norm) * mu : Vec3<double>{0.0, 0.0, 0.0};
}

// UAMMD-structured's magnet: "mx my mz" per particle, the frames one after the other with no header.
class MagnetWriter final : public TextTrajectoryWriter {
public:
    using TextTrajectoryWriter::TextTrajectoryWriter;
    bool needs_moments() const override { return true; }

protected:
    void write_frame(std::FILE* f, const TrajectoryFrame& frame) override {
        for (size_t i = 0; i < frame.ids.size(); ++i) {
            const Vec3<double> mu = moment_of(frame, i);
            std::fprintf(f, "%.8g %.8g %.8g\n", mu.x, mu.y, mu.z);
        }
    }
};

// UAMMD-structured's xyzm: "x y z mx my mz" per particle, the frames one after the other with no header.
class XyzmWriter final : public TextTrajectoryWriter {
public:
    using TextTrajectoryWriter::TextTrajectoryWriter;
    bool needs_moments() const override { return true; }

protected:
    void write_frame(std::FILE* f, const TrajectoryFrame& frame) override {
        for (size_t i = 0; i < frame.ids.size(); ++i) {
            const Vec3<double> p = position_of(frame, i), mu = moment_of(frame, i);
            std::fprintf(f, "%.8g %.8g %.8g %.8g %.8g %.8g\n", p.x, p.y, p.z, mu.x, mu.y, mu.z);
        }
    }
};

// UAMMD-structured's spm (superpunto with moments): per particle the sp line "x y z radius type",
// then a small sphere (radius / 5) on its surface along its moment, "x+a*u y+a*u z+a*u radius/5 type+1".
class SpmWriter final : public TextTrajectoryWriter {
public:
    using TextTrajectoryWriter::TextTrajectoryWriter;
    bool needs_moments() const override { return true; }

protected:
    void write_frame(std::FILE* f, const TrajectoryFrame& frame) override {
        write_sp_header(f, frame);
        for (size_t i = 0; i < frame.types.size(); ++i) {
            const Vec3<double> p = position_of(frame, i);
            const double a = frame.radii[i];
            write_sphere(f, p, a, frame.types[i]);
            const Vec3<double> m = p + a * moment_direction(frame, i);
            write_sphere(f, m, 0.2 * a, frame.types[i] + 1);
        }
    }
};

// UAMMD-structured's svvm (for SVV3D): "# SPHERE OPACITY 0.6" once at the top of the file, then per
// frame the sp header and per particle the sp line and an arrow "x y z vx vy vz color" through the
// particle along its moment, from p - 0.9 a u, of length 1.8 a, colored 7 for type 1 and 1 otherwise.
class SvvmWriter final : public TextTrajectoryWriter {
public:
    using TextTrajectoryWriter::TextTrajectoryWriter;
    bool needs_moments() const override { return true; }

protected:
    void write_frame(std::FILE* f, const TrajectoryFrame& frame) override {
        if (frames() == 0) std::fprintf(f, "# SPHERE OPACITY 0.6\n");
        write_sp_header(f, frame);
        for (size_t i = 0; i < frame.types.size(); ++i) {
            const Vec3<double> p = position_of(frame, i), u = moment_direction(frame, i);
            const double a = frame.radii[i];
            const int type = frame.types[i];
            write_sphere(f, p, a, type);
            const Vec3<double> tail = p - (0.9 * a) * u, arrow = (1.8 * a) * u;
            std::fprintf(f, "%.8g %.8g %.8g %.8g %.8g %.8g %d\n", tail.x, tail.y, tail.z, arrow.x, arrow.y, arrow.z,
                         type != 1 ? 1 : 7);
        }
    }
    // Appending to a file that has frames already: the opacity line is there.
    void count_existing_frames() override { set_frames(1); }
};

// UAMMD-structured's svvma: per frame the sp header, per particle the sp line, an arrow of length 2a
// along the moment colored 1, and the anisotropy (easy) axis, the body's z axis, as two arrows of
// length 2a either way colored 39.
class SvvmaWriter final : public TextTrajectoryWriter {
public:
    using TextTrajectoryWriter::TextTrajectoryWriter;
    bool needs_moments() const override { return true; }
    bool needs_orientations() const override { return true; }

protected:
    void write_frame(std::FILE* f, const TrajectoryFrame& frame) override {
        write_sp_header(f, frame);
        for (size_t i = 0; i < frame.types.size(); ++i) {
            const Vec3<double> p = position_of(frame, i);
            const double a = frame.radii[i];
            write_sphere(f, p, a, frame.types[i]);
            const Vec3<double> m = (2.0 * a) * moment_direction(frame, i), z = (2.0 * a) * body_axes(frame, i).z;
            std::fprintf(f, "%.8g %.8g %.8g %.8g %.8g %.8g 1\n", p.x, p.y, p.z, m.x, m.y, m.z);
            std::fprintf(f, "%.8g %.8g %.8g %.8g %.8g %.8g 39\n", p.x, p.y, p.z, z.x, z.y, z.z);
            std::fprintf(f, "%.8g %.8g %.8g %.8g %.8g %.8g 39\n", p.x, p.y, p.z, -z.x, -z.y, -z.z);
        }
    }
};

}  // namespace

const std::vector<std::string>& trajectory_formats() {
    static const std::vector<std::string> names{"xyz", "sp", "spf", "lammpstrj", "dcd", "pdb", "coord", "vel", "itpv",
                                                "spo", "svv", "itpd", "magnet", "xyzm", "spm", "svvm", "svvma"};
    return names;
}

std::unique_ptr<TrajectoryWriter> make_trajectory_writer(const std::string& format, TrajectoryOptions options) {
    if (format == "xyz") return std::make_unique<XyzWriter>(std::move(options));
    if (format == "sp") return std::make_unique<SpWriter>(std::move(options));
    if (format == "spf") return std::make_unique<SpfWriter>(std::move(options));
    if (format == "coord") return std::make_unique<CoordWriter>(std::move(options));
    if (format == "vel") return std::make_unique<VelocityWriter>(std::move(options));
    if (format == "itpv") return std::make_unique<ItpvWriter>(std::move(options));
    if (format == "spo") return std::make_unique<SpoWriter>(std::move(options));
    if (format == "svv") return std::make_unique<SvvWriter>(std::move(options));
    if (format == "itpd") return std::make_unique<ItpdWriter>(std::move(options));
    if (format == "lammpstrj") return std::make_unique<LammpsDumpWriter>(std::move(options));
    if (format == "dcd") return std::make_unique<DcdWriter>(std::move(options));
    if (format == "pdb") return std::make_unique<PdbWriter>(std::move(options));
    if (format == "magnet") return std::make_unique<MagnetWriter>(std::move(options));
    if (format == "xyzm") return std::make_unique<XyzmWriter>(std::move(options));
    if (format == "spm") return std::make_unique<SpmWriter>(std::move(options));
    if (format == "svvm") return std::make_unique<SvvmWriter>(std::move(options));
    if (format == "svvma") return std::make_unique<SvvmaWriter>(std::move(options));
    return nullptr;
}

}  // namespace structmd
