// The table of every trajectory format: the text formats described by their columns (text_format.hpp)
// — xyz, sp, spf, lammpstrj, and UAMMD-structured's coord, vel, itpv, the orientation formats spo,
// svv and itpd and the magnetic ones magnet, xyzm, spm, svvm and svvma — beside dcd and pdb, which
// have writers of their own. Values are written with 8 significant digits.
#include <cmath>
#include <cstdio>
#include <functional>

#include "steps/dcd_writer.hpp"
#include "steps/pdb_writer.hpp"
#include "steps/text_format.hpp"
#include "steps/trajectory_writer.hpp"

namespace structmd {

Error trajectory_io_error(const TrajectoryOptions& options, const std::string& action, const std::string& reason) {
    return Error(STRUCTMD_ERR_IO, options.owner + ": cannot " + action + " '" + options.path + "': " + reason);
}

namespace {

// ---- frame headers ----

// The extended-XYZ frame header: N, then a comment line with step, time and box.
void extended_xyz_header(std::FILE* f, const TrajectoryFrame& frame) {
    const auto& L = frame.box;
    std::fprintf(f,
                 "%zu\nstep=%lld time=%.8g Lattice=\"%.8g 0 0 0 %.8g 0 0 0 %.8g\" "
                 "Properties=species:S:1:pos:R:3:Z:I:1:type:I:1 pbc=\"T T T\"\n",
                 frame.ids.size(), static_cast<long long>(frame.step), frame.time, L[0], L[1], L[2]);
}

// The superpunto frame header: the half box lengths.
void superpunto_header(std::FILE* f, const TrajectoryFrame& frame) {
    const auto& L = frame.box;
    std::fprintf(f, "#Lx=%.8g;Ly=%.8g;Lz=%.8g;\n", 0.5 * L[0], 0.5 * L[1], 0.5 * L[2]);
}

// A LAMMPS text dump's frame header; xu yu zu mark unwrapped positions.
void lammps_header(std::FILE* f, const TrajectoryFrame& frame) {
    std::fprintf(f, "ITEM: TIMESTEP\n%lld\nITEM: NUMBER OF ATOMS\n%zu\nITEM: BOX BOUNDS pp pp pp\n",
                 static_cast<long long>(frame.step), frame.ids.size());
    for (double L : frame.box) std::fprintf(f, "%.8g %.8g\n", -0.5 * L, 0.5 * L);
    std::fprintf(f, frame.wrapped ? "ITEM: ATOMS id type x y z\n" : "ITEM: ATOMS id type xu yu zu\n");
}

// N and an empty line.
void particle_count_header(std::FILE* f, const TrajectoryFrame& frame) { std::fprintf(f, "%zu\n\n", frame.ids.size()); }

// ---- columns ----

using P = WrittenParticle;

void id(const P& p, LinePrinter& line) { line.integer(p.id()); }
void type(const P& p, LinePrinter& line) { line.integer(p.type()); }
void type_name(const P& p, LinePrinter& line) { line.text(p.type_name()); }
void atomic_number_of_type(const P& p, LinePrinter& line) { line.integer(p.atomic_number()); }
void position(const P& p, LinePrinter& line) { line.reals(p.position()); }
void radius(const P& p, LinePrinter& line) { line.real(p.radius()); }
void velocity(const P& p, LinePrinter& line) { line.reals(p.velocity()); }
void force(const P& p, LinePrinter& line) { line.reals(p.force()); }
void moment(const P& p, LinePrinter& line) { line.reals(p.moment()); }
void speed(const P& p, LinePrinter& line) {
    const Vec3<double> v = p.velocity();
    line.real(std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z));
}
void quaternion(const P& p, LinePrinter& line) {
    for (int k = 0; k < 4; ++k) line.real(p.quaternion()[k]);
}
// LAMMPS counts ids and types from 1.
void id_from_one(const P& p, LinePrinter& line) { line.integer(p.id() + 1); }
void type_from_one(const P& p, LinePrinter& line) { line.integer(p.type() + 1); }

Column integer(std::function<int64_t(const P&)> value) {
    return [value](const P& p, LinePrinter& line) { line.integer(value(p)); };
}

// A unit direction of a particle in the lab frame.
using Direction = std::function<Vec3<double>(const P&)>;
Vec3<double> moment_direction(const P& p) { return p.moment_direction(); }
Direction body_axis(int axis) {
    return [axis](const P& p) { return p.body_axis(axis); };
}

// ---- lines ----

// The superpunto sphere: "x y z radius type".
TextLine sphere() { return {position, radius, type}; }

// A small sphere (radius / 5) on the particle's surface along a direction: "x+a*u y+a*u z+a*u a/5 t".
TextLine surface_marker(Direction along, std::function<int64_t(const P&)> markerType) {
    return {[along](const P& p, LinePrinter& line) { line.reals(p.position() + p.radius() * along(p)); },
            [](const P& p, LinePrinter& line) { line.real(0.2 * p.radius()); }, integer(std::move(markerType))};
}

// An arrow from the particle's centre, `scale` radii long: "x y z vx vy vz color" (SVV3D).
TextLine arrow(Direction along, double scale, int color) {
    return {position, [along, scale](const P& p, LinePrinter& line) { line.reals((scale * p.radius()) * along(p)); },
            integer([color](const P&) { return color; })};
}

// An arrow through the particle along its moment, from p - 0.9 a u, of length 1.8 a, colored 7 for
// type 1 and 1 otherwise.
TextLine moment_arrow_through() {
    return {[](const P& p, LinePrinter& line) { line.reals(p.position() - (0.9 * p.radius()) * p.moment_direction()); },
            [](const P& p, LinePrinter& line) { line.reals((1.8 * p.radius()) * p.moment_direction()); },
            integer([](const P& p) { return p.type() != 1 ? 1 : 7; })};
}

// ---- the table ----

struct FormatEntry {
    std::string name;  // also the file extension
    std::function<std::unique_ptr<TrajectoryWriter>(TrajectoryOptions)> make;
};

FormatEntry text(std::string name, FrameStart start, std::vector<TextLine> lines, unsigned needs = 0,
                 std::string fileHeader = {}) {
    const TextFormat format{start, std::move(lines), needs, std::move(fileHeader)};
    return {std::move(name), [format](TrajectoryOptions options) {
                return std::make_unique<TextFormatWriter>(std::move(options), format);
            }};
}

const std::vector<FormatEntry>& format_entries() {
    static const std::vector<FormatEntry> entries{
        // "species x y z Z type": Z is the atomic number of a type name that is an element, else 0
        // (which ASE reads as a dummy atom instead of failing on a coarse-grained name).
        text("xyz", extended_xyz_header, {{type_name, position, atomic_number_of_type, type}}),
        text("sp", superpunto_header, {sphere()}),
        text("spf", superpunto_header, {{position, radius, type, force}}, kForces),
        text("lammpstrj", lammps_header, {{id_from_one, type_from_one, position}}),
        {"dcd", [](TrajectoryOptions options) { return std::make_unique<DcdWriter>(std::move(options)); }},
        {"pdb", make_pdb_writer},
        // coord, vel, magnet and xyzm: the frames one after the other with no line between them.
        text("coord", nullptr, {{id, position, velocity}}, kVelocities),
        text("vel", nullptr, {{velocity, speed}}, kVelocities),
        text("itpv", particle_count_header, {{id, type, position, velocity}}, kVelocities),
        // spo: the body axes marked by small spheres of types 2, 3 and 4 times the particle's.
        text("spo", superpunto_header,
             {sphere(), surface_marker(body_axis(0), [](const P& p) { return 2 * p.type(); }),
              surface_marker(body_axis(1), [](const P& p) { return 3 * p.type(); }),
              surface_marker(body_axis(2), [](const P& p) { return 4 * p.type(); })},
             kOrientations),
        // svv: the body axes as arrows of length twice the radius, colored 1 (x), 5 (y) and 8 (z).
        text("svv", superpunto_header,
             {sphere(), arrow(body_axis(0), 2.0, 1), arrow(body_axis(1), 2.0, 5), arrow(body_axis(2), 2.0, 8)},
             kOrientations),
        text("itpd", particle_count_header, {{id, type, position, quaternion}}, kOrientations),
        text("magnet", nullptr, {{moment}}, kMoments),
        text("xyzm", nullptr, {{position, moment}}, kMoments),
        text("spm", superpunto_header,
             {sphere(), surface_marker(moment_direction, [](const P& p) { return p.type() + 1; })}, kMoments),
        text("svvm", superpunto_header, {sphere(), moment_arrow_through()}, kMoments, "# SPHERE OPACITY 0.6\n"),
        // svvma: the moment (color 1) and the anisotropy (easy) axis, the body's z axis, both ways
        // (color 39), as arrows of length twice the radius.
        text("svvma", superpunto_header,
             {sphere(), arrow(moment_direction, 2.0, 1), arrow(body_axis(2), 2.0, 39),
              arrow([](const P& p) { return -p.body_axis(2); }, 2.0, 39)},
             kMoments | kOrientations),
    };
    return entries;
}

}  // namespace

const std::vector<std::string>& trajectory_formats() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> all;
        for (const FormatEntry& entry : format_entries()) all.push_back(entry.name);
        return all;
    }();
    return names;
}

std::unique_ptr<TrajectoryWriter> make_trajectory_writer(const std::string& format, TrajectoryOptions options) {
    for (const FormatEntry& entry : format_entries())
        if (entry.name == format) return entry.make(std::move(options));
    return nullptr;
}

}  // namespace structmd
