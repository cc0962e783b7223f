#pragma once
// Tabulated potentials: ["NonBonded","Tabulated"] and ["Bond2"|"Bond3"|"Bond4","Tabulated"].
// Energy and force are given on a grid, inline or in a LAMMPS table file, and interpolated as
// LAMMPS's `table spline N` styles do (table_spline.hpp): the reader (tabulated_read.cpp) resamples
// each table onto N even nodes and splines it once, and these functors evaluate that spline.
//
// Outside its table a term has no value (LAMMPS stops with "Pair distance < table inner cutoff",
// "Bond length < table inner cutoff", ...). A kernel cannot stop, so the functors return NaN energy
// and forces there, and the engine reports a numerical fault naming the step and the particle. A pair
// beyond the cutoff does not interact, as for every pair term.
#include <limits>
#include <memory>
#include <vector>

#include "core/registry.hpp"
#include "forcefield/bond_potential.hpp"
#include "forcefield/bonded_geometry.hpp"
#include "forcefield/dihedral.hpp"
#include "forcefield/forcefield_spec.hpp"
#include "forcefield/interactor_build.hpp"
#include "forcefield/interactor_tables.hpp"
#include "forcefield/pair_interaction.hpp"
#include "forcefield/table_spline.hpp"

namespace structmd {

struct ForceFieldComponent;  // component_registry.hpp (the reader's side; this header stays free of JSON)

// What the reader derives from a NonBonded table entry: one resampled table per listed type pair.
struct PairTableConfig : ComponentConfig {
    struct Row {
        int typeI, typeJ;
        double cutoff;
        TableNodes nodes;  // in r^2, force / r
    };
    std::vector<Row> rows;
};

// What the reader derives from a bond table entry: one table shared by all its bonds.
struct BondTableConfig : ComponentConfig {
    TableNodes nodes;
    double upper = 0.0;  // the largest abscissa the table covers (its lowest is nodes.x0)
};

namespace table_detail {

template <class R>
SMD_HD SMD_INLINE R nan() {
    return std::numeric_limits<R>::quiet_NaN();
}

// A bond outside its table: NaN forces on its N particles and NaN energy, for the engine to report.
template <int N, class R>
SMD_HD SMD_INLINE R outside_table(Vec3<R>* force) {
    for (int k = 0; k < N; ++k) force[k] = {nan<R>(), nan<R>(), nan<R>()};
    return nan<R>();
}

// The coefficients of every table of a config, in R, on the backend, and where each table starts.
template <class B, class R>
std::shared_ptr<typename B::template Buffer<R>> upload(const B& backend, const std::vector<const TableNodes*>& tables,
                                                       std::vector<size_t>& offsets) {
    std::vector<R> host;
    for (const TableNodes* t : tables) {
        offsets.push_back(host.size());
        for (double c : t->coefficients) host.push_back(R(c));
    }
    auto buffer = std::make_shared<typename B::template Buffer<R>>();
    backend.upload(*buffer, host.data(), host.size());
    return buffer;
}

}  // namespace table_detail

// The pair functor: the spline in r^2 of energy and force / r, from the inner radius to the cutoff.
struct TabulatedPairPotential {
    template <class R>
    struct Params {
        UniformSpline<R> table;
        R cutoff2;
    };

    template <class R>
    static SMD_HD SMD_INLINE PairTerm<R> evaluate(R r2, const Params<R>& p) {
        if (!(r2 >= p.table.x0)) return {table_detail::nan<R>(), table_detail::nan<R>()};
        const SplineSample<R> s = evaluate_spline(p.table, r2);
        return {-s.force, s.energy};  // the table holds F / r = -U'(r) / r
    }
};

// What every bond of a bond table entry reads: the table, the largest abscissa it covers (its lowest
// is table.x0), and whether its force is the energy's derivative (a dihedral table without forces).
template <class R>
struct BondTableParams {
    UniformSpline<R> table;
    R upper;
    bool forceFromEnergy;
};

// What the bond table functors share: their arity and the Params every bond of the entry reads.
template <int N>
struct BondTable {
    static constexpr int arity = N;
    template <class R>
    using Params = BondTableParams<R>;
};

// Two-particle bond: the spline in r over [lo, hi] of the table.
struct TabulatedBondPotential : BondTable<2> {
    template <class R>
    static SMD_HD SMD_INLINE R compute(const Vec3<R>* r, const BondTableParams<R>& p, const Box<R>&, Vec3<R>* force) {
        const Vec3<R> d = r[1] - r[0];
        const R length = sqrt(dot(d, d));
        if (!(length >= p.table.x0 && length <= p.upper)) return table_detail::outside_table<2>(force);
        const SplineSample<R> s = evaluate_spline(p.table, length);
        // F = -U'(r) along r[1] - r[0] pushes r[1] away when positive.
        force[1] = length > R(0) ? (s.force / length) * d : Vec3<R>{0, 0, 0};
        force[0] = -force[1];
        return s.energy;
    }
};

// Angle of three particles: the spline in theta over [0, pi] (theta at the middle particle, as for
// ["Bond3","HarmonicAngular"]; bonded_geometry.hpp).
struct TabulatedAnglePotential : BondTable<3> {
    template <class R>
    static SMD_HD SMD_INLINE R compute(const Vec3<R>* r, const BondTableParams<R>& p, const Box<R>&, Vec3<R>* force) {
        const bonded_geometry::BondAngle<R> angle = bonded_geometry::bond_angle(r[0] - r[1], r[2] - r[1]);
        if (!(angle.theta >= R(0) && angle.theta <= p.upper)) return table_detail::outside_table<3>(force);
        const SplineSample<R> s = evaluate_spline(p.table, angle.theta);
        force[0] = s.force * angle.dtheta_da;  // the table's force is -dU/dtheta
        force[2] = s.force * angle.dtheta_db;
        force[1] = -(force[0] + force[2]);
        return s.energy;
    }
};

// Dihedral of four particles: the periodic spline in phi over [0, 2 pi), phi the IUPAC dihedral
// (bonded_geometry.hpp) taken in [0, 2 pi) as LAMMPS's dihedral_style table does. A chain with three
// collinear particles has no dihedral: as for ["Bond4","Dihedral"], it feels no force and its
// energy is the table's at phi = 0.
struct TabulatedDihedralPotential : BondTable<4> {
    template <class R>
    static SMD_HD SMD_INLINE R compute(const Vec3<R>* r, const BondTableParams<R>& p, const Box<R>&, Vec3<R>* force) {
        const bonded_geometry::DihedralAngle<R> angle = bonded_geometry::dihedral_of(r);
        const R phi = angle.phi < R(0) ? angle.phi + R(2 * M_PI) : angle.phi;
        const SplineSample<R> s = evaluate_spline(p.table, phi);
        const R minusSlope = p.forceFromEnergy ? energy_spline_force(p.table, phi) : s.force;
        bonded_geometry::write_dihedral_forces(angle, -minusSlope, force);
        return s.energy;
    }
};

// ["NonBonded","Tabulated"]
struct TabulatedPair {
    static ForceFieldComponent reader_entry(ComponentKey key);

    template <class B, class R, class PairR>
    static std::unique_ptr<Interactor<B, R>> make_interactor(const InteractorBuild<B, R>& build, const InteractionSpec& s) {
        using Params = TabulatedPairPotential::Params<PairR>;
        const auto& pair = static_cast<const PairSpec&>(s);
        const auto& config = static_cast<const PairTableConfig&>(*s.config);
        std::vector<const TableNodes*> tables;
        for (const PairTableConfig::Row& row : config.rows) tables.push_back(&row.nodes);
        std::vector<size_t> offsets;
        const auto nodes = table_detail::upload<B, PairR>(build.backend, tables, offsets);
        const size_t ntypes = build.context.ntypes;
        std::vector<Params> table(ntypes * ntypes, Params{});  // cutoff2 = 0: unlisted pairs do not interact
        for (size_t k = 0; k < config.rows.size(); ++k) {
            const PairTableConfig::Row& row = config.rows[k];
            const Params p{uniform_spline<PairR>(row.nodes, nodes->data() + offsets[k]), PairR(row.cutoff * row.cutoff)};
            table[row.typeI * ntypes + row.typeJ] = p;
            table[row.typeJ * ntypes + row.typeI] = p;
        }
        auto interactor = std::make_unique<PairInteraction<B, R, TabulatedPairPotential, PairR>>(
            build.backend, build.scope(pair), build.listFor(pair), table, static_cast<int>(ntypes));
        interactor->own(nodes);
        return interactor;
    }
};

// The engine side of a bond table entry: every bond of the entry reads the one table.
template <class Potential, class B, class R>
std::unique_ptr<Interactor<B, R>> make_table_bond_interaction(const InteractorBuild<B, R>& build, const InteractionSpec& s) {
    const auto& config = static_cast<const BondTableConfig&>(*s.config);
    std::vector<size_t> offsets;
    const auto nodes = table_detail::upload<B, R>(build.backend, {&config.nodes}, offsets);
    const BondTableParams<R> p{uniform_spline<R>(config.nodes, nodes->data()), R(config.upper),
                               config.nodes.forceFromEnergy};
    auto interactor = make_bond_interaction<B, R, Potential>(build, static_cast<const BondSpec&>(s),
                                                             [&](const ParameterValues&) { return p; });
    interactor->own(nodes);
    return interactor;
}

// ["Bond2","Tabulated"]
struct TabulatedBond {
    static ForceFieldComponent reader_entry(ComponentKey key);
    template <class B, class R, class PairR>
    static std::unique_ptr<Interactor<B, R>> make_interactor(const InteractorBuild<B, R>& build, const InteractionSpec& s) {
        return make_table_bond_interaction<TabulatedBondPotential>(build, s);
    }
};

// ["Bond3","Tabulated"]
struct TabulatedAngle {
    static ForceFieldComponent reader_entry(ComponentKey key);
    template <class B, class R, class PairR>
    static std::unique_ptr<Interactor<B, R>> make_interactor(const InteractorBuild<B, R>& build, const InteractionSpec& s) {
        return make_table_bond_interaction<TabulatedAnglePotential>(build, s);
    }
};

// ["Bond4","Tabulated"]
struct TabulatedDihedral {
    static ForceFieldComponent reader_entry(ComponentKey key);
    template <class B, class R, class PairR>
    static std::unique_ptr<Interactor<B, R>> make_interactor(const InteractorBuild<B, R>& build, const InteractionSpec& s) {
        return make_table_bond_interaction<TabulatedDihedralPotential>(build, s);
    }
};

}  // namespace structmd
