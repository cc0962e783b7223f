// Reading ["Surface","WCA_Polyhedron"]: its mesh from the entry's "parameters" ("vertex": [[x, y, z],
// ...], "faces": [[i, j, k], ...]), checked here so that the functor never reads outside it; its
// epsilon and sigma per type from its table, as every Surface entry (read_forcefield.cpp).
#include "forcefield/wca_polyhedron.hpp"

#include <cmath>
#include <string>

#include "core/error.hpp"
#include "forcefield/component_registry.hpp"
#include "input/read_parameters.hpp"

namespace structmd {

using input::ComponentEntry;
using input::SystemDescription;
using input::TrackedNode;

namespace {

// A list of rows of three numbers, by its path's name.
TrackedNode rows_of_three(const TrackedNode& params, const char* key, const char* what) {
    const TrackedNode list = params.at(key);
    if (!list.is_array() || list.size() == 0) throw input_error(list.path(), std::string("expected a list of ") + what);
    for (size_t k = 0; k < list.size(); ++k) {
        const TrackedNode row = list.at(k);
        if (!row.is_array() || row.size() != 3) throw input_error(row.path(), std::string("expected ") + what);
    }
    return list;
}

ForceFieldComponent configure(ForceFieldComponent c, const ComponentEntry& entry) {
    const TrackedNode params = input::parameters_of(entry.node);
    if (!params.valid()) throw input_error(entry.node.path() + ".parameters", "missing: the mesh (vertex and faces)");
    auto mesh = std::make_shared<PolyhedronConfig>();
    const TrackedNode vertices = rows_of_three(params, "vertex", "vertices [x, y, z]");
    for (size_t k = 0; k < vertices.size(); ++k) {
        const TrackedNode row = vertices.at(k);
        Vec3<double> x{row.at(size_t{0}).as<double>(), row.at(size_t{1}).as<double>(), row.at(size_t{2}).as<double>()};
        if (!std::isfinite(x.x) || !std::isfinite(x.y) || !std::isfinite(x.z))
            throw input_error(row.path(), "expected finite coordinates");
        mesh->vertices.push_back(x);
    }
    const TrackedNode faces = rows_of_three(params, "faces", "faces [i, j, k] (indices into vertex)");
    for (size_t f = 0; f < faces.size(); ++f) {
        const TrackedNode row = faces.at(f);
        int ids[3];
        for (size_t m = 0; m < 3; ++m) {
            const TrackedNode cell = row.at(m);
            const int64_t id = cell.as<int64_t>();
            if (id < 0 || id >= static_cast<int64_t>(mesh->vertices.size()))
                throw input_error(cell.path(), "vertex " + std::to_string(id) + " does not exist (vertices are 0.." +
                                                   std::to_string(mesh->vertices.size() - 1) + ")");
            ids[m] = static_cast<int>(id);
            mesh->faces.push_back(ids[m]);
        }
        // A face of no area has no plane (the reference divides by its zero normal).
        const Vec3<double> a = mesh->vertices[ids[0]];
        const Vec3<double> n = bonded_geometry::cross(mesh->vertices[ids[1]] - a, mesh->vertices[ids[2]] - a);
        if (!(dot(n, n) > 0.0)) throw input_error(row.path(), "the face has no area (its vertices are on one line)");
    }
    c.config = mesh;
    return c;
}

}  // namespace

ForceFieldComponent WCAPolyhedron::reader_entry(ComponentKey key) {
    ForceFieldComponent c;
    c.key = std::move(key);
    c.kind = InteractionKind::external;
    c.typeParameters = {number("epsilon", "energy"), number("sigma", "length", Must::be_positive)};
    c.configure = [c](const ComponentEntry& entry, const SystemDescription&) { return configure(c, entry); };
    return c;
}

}  // namespace structmd
