#pragma once
// UAMMD-structured's ["Surface","WCA_Polyhedron"]: a surface made of triangles (the entry's "vertex"
// list and its "faces", three vertex indices each), and the WCA type 1 potential of a particle's
// distance to it, with an epsilon and a sigma per type:
//   U = 4 eps [(sigma/g)^12 - (sigma/g)^6] + eps   for g < 2^(1/6) sigma, else 0,   F = -dU/dg v/g
// where v runs from the point of the surface nearest to the particle to the particle, g = |v|. The
// nearest point is the nearest over every face of the foot of the perpendicular (where it falls inside
// the triangle) and of the nearest point of each of its edges (their ends included), so g is the
// distance to the whole surface, on either side of it (the surface need not be closed; the order of a
// face's vertices plays no part). Its mesh is read by wca_polyhedron_read.cpp into a PolyhedronConfig;
// the functor reads it from backend memory through its Params.
#include <memory>
#include <vector>

#include "forcefield/bonded_geometry.hpp"
#include "forcefield/external_potential.hpp"
#include "forcefield/forcefield_spec.hpp"
#include "forcefield/interactor_build.hpp"
#include "forcefield/interactor_tables.hpp"
#include "forcefield/lennard_jones.hpp"

namespace structmd {

struct ForceFieldComponent;  // component_registry.hpp (the reader's side; this header stays free of JSON)

// What the reader derives from the entry: the mesh.
struct PolyhedronConfig : ComponentConfig {
    std::vector<Vec3<double>> vertices;
    std::vector<int> faces;  // three vertex indices per face
};

struct WCAPolyhedronPotential {
    template <class R>
    struct Params {
        const Vec3<R>* vertices;
        const int* faces;
        int faceCount;
        LennardJonesParams<R> wca;
    };

    // The WCA parameters of a type, with the mesh in backend memory.
    template <class R>
    static Params<R> make_params(const ParameterValues& v, const Vec3<R>* vertices, const int* faces, int faceCount) {
        const double sigma = v["sigma"], epsilon = v["epsilon"];
        const double cutoff = LennardJonesShape1::minimum_distance(sigma);
        return {vertices, faces, faceCount, {R(epsilon), R(sigma * sigma), R(cutoff * cutoff), R(epsilon)}};
    }

    template <class R>
    static SMD_HD SMD_INLINE R compute(Vec3<R> r, R, const Params<R>& p, R, Vec3<R>& force) {
        force = {R(0), R(0), R(0)};
        if (p.faceCount == 0) return R(0);
        Vec3<R> v = r - p.vertices[p.faces[0]];  // a first candidate: a vertex
        R nearest2 = dot(v, v);
        for (int f = 0; f < p.faceCount; ++f) {
            const Vec3<R> a = p.vertices[p.faces[3 * f]], b = p.vertices[p.faces[3 * f + 1]],
                          c = p.vertices[p.faces[3 * f + 2]];
            const Vec3<R> n = bonded_geometry::cross(b - a, c - a);
            // The foot of the perpendicular lies in the triangle when r is on the inner side of all three
            // edges (the same side as the triangle, seen along n).
            if (dot(bonded_geometry::cross(b - a, r - a), n) >= R(0) &&
                dot(bonded_geometry::cross(c - b, r - b), n) >= R(0) &&
                dot(bonded_geometry::cross(a - c, r - c), n) >= R(0))
                keep_nearer((dot(r - a, n) / dot(n, n)) * n, nearest2, v);
            keep_nearer(from_segment(r, a, b), nearest2, v);
            keep_nearer(from_segment(r, b, c), nearest2, v);
            keep_nearer(from_segment(r, c, a), nearest2, v);
        }
        const PairTerm<R> term = evaluate_lennard_jones<LennardJonesShape1>(nearest2, p.wca);
        // F = -(dU/dg / g) v; dudr_over_r is dU/dg / g.
        force = (-term.dudr_over_r) * v;
        return term.energy;
    }

private:
    template <class R>
    static SMD_HD SMD_INLINE void keep_nearer(Vec3<R> candidate, R& nearest2, Vec3<R>& v) {
        const R g2 = dot(candidate, candidate);
        if (g2 < nearest2) {
            nearest2 = g2;
            v = candidate;
        }
    }

    // From the point of the segment [a, b] nearest to r, to r.
    template <class R>
    static SMD_HD SMD_INLINE Vec3<R> from_segment(Vec3<R> r, Vec3<R> a, Vec3<R> b) {
        const Vec3<R> ab = b - a;
        R t = dot(r - a, ab) / dot(ab, ab);
        t = t < R(0) ? R(0) : (t > R(1) ? R(1) : t);
        return r - (a + t * ab);
    }
};

// ["Surface","WCA_Polyhedron"]: a configurable component (its mesh is part of its entry).
struct WCAPolyhedron {
    static ForceFieldComponent reader_entry(ComponentKey key);

    template <class B, class R, class PairR>
    static std::unique_ptr<Interactor<B, R>> make_interactor(const InteractorBuild<B, R>& build,
                                                             const InteractionSpec& s) {
        const auto& external = static_cast<const ExternalSpec&>(s);
        const auto& mesh = static_cast<const PolyhedronConfig&>(*s.config);
        const int faceCount = static_cast<int>(mesh.faces.size() / 3);
        auto faces = std::make_shared<typename B::template Buffer<int>>();
        build.backend.upload(*faces, mesh.faces.data(), mesh.faces.size());
        const TypedExternalLayout layout(build, external);
        // The vertices in real type T on the backend, and the table of Params pointing into them.
        const auto tableIn = [&](auto real, auto& vertices) {
            using T = decltype(real);
            std::vector<Vec3<T>> host;
            for (const Vec3<double>& x : mesh.vertices) host.push_back({T(x.x), T(x.y), T(x.z)});
            vertices = std::make_shared<typename B::template Buffer<Vec3<T>>>();
            build.backend.upload(*vertices, host.data(), host.size());
            return layout.template table<WCAPolyhedronPotential::Params<T>>([&](const ParameterValues& v) {
                return WCAPolyhedronPotential::make_params<T>(v, vertices->data(), faces->data(), faceCount);
            });
        };
        std::shared_ptr<typename B::template Buffer<Vec3<R>>> vertices;
        auto interactor = layout.template make<WCAPolyhedronPotential>(build, tableIn(R{}, vertices));
        interactor->own(faces);
        interactor->own(vertices);
        if (build.context.hessian) {
            std::shared_ptr<typename B::template Buffer<Vec3<Dual<R>>>> dualVertices;
            interactor->enable_hessian(tableIn(Dual<R>{}, dualVertices));
            interactor->own(dualVertices);
        }
        return interactor;
    }
};

}  // namespace structmd
