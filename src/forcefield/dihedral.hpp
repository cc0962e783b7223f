#pragma once
// Dihedral (torsion) terms of four particles, in the IUPAC angle phi of the chain r[0]-r[1]-r[2]-r[3]
// (phi in [-pi, pi], cis = 0, trans = pi; bonded_geometry.hpp):
//   Dihedral:  U = K [1 + cos(n phi - phi0)]
//   Dihedral4: U = sum_{n=1..4} K_n [1 + cos(n phi - phi0_n)]
// A chain with three consecutive particles collinear has no dihedral: it feels no force from these
// terms, and its energy is taken at phi = 0.
#include "forcefield/bond_potential.hpp"
#include "forcefield/bonded_geometry.hpp"

namespace structmd {

struct Dihedral {
    static constexpr int arity = 4;

    template <class R>
    struct Params {
        R n;  // multiplicity, an integer (the reader checks it) kept as a real for the arithmetic
        R K;
        R phi0;
    };

    static std::vector<Parameter> parameters() {
        return {number("n", "1", Must::be_integer), number("K", "energy"), number("phi0", "radian")};
    }
    template <class R>
    static Params<R> make_params(const ParameterValues& v, const Constants&) {
        return {R(v["n"]), R(v["K"]), R(v["phi0"])};
    }

    template <class R>
    static SMD_HD SMD_INLINE R compute(const Vec3<R>* r, const Params<R>& p, const Box<R>&, Vec3<R>* force) {
        const bonded_geometry::DihedralAngle<R> angle = bonded_geometry::dihedral_of(r);
        const R phase = p.n * angle.phi - p.phi0;
        bonded_geometry::write_dihedral_forces<R>(angle, -p.K * p.n * sin(phase), force);
        return p.K * (R(1) + cos(phase));
    }
};

struct Dihedral4 {
    static constexpr int arity = 4;

    template <class R>
    struct Params {
        R K[4];     // K_n for n = 1..4
        R phi0[4];  // phi0_n for n = 1..4
        R offset;   // added to U: 0 here; a Fourier series written in this form (IDP_Fourier) takes -sum K_n
    };

    static std::vector<Parameter> parameters() { return {numbers("K", 4, "energy"), numbers("phi0", 4, "radian")}; }
    template <class R>
    static Params<R> make_params(const ParameterValues& v, const Constants&) {
        Params<R> p;
        for (int k = 0; k < 4; ++k) {
            p.K[k] = R(v.vector("K")[k]);
            p.phi0[k] = R(v.vector("phi0")[k]);
        }
        p.offset = R(0);
        return p;
    }

    template <class R>
    static SMD_HD SMD_INLINE R compute(const Vec3<R>* r, const Params<R>& p, const Box<R>&, Vec3<R>* force) {
        const bonded_geometry::DihedralAngle<R> angle = bonded_geometry::dihedral_of(r);
        R energy = p.offset;
        R dudphi = 0;
        for (int k = 0; k < 4; ++k) {
            const R n = R(k + 1);
            const R phase = n * angle.phi - p.phi0[k];
            energy += p.K[k] * (R(1) + cos(phase));
            dudphi -= p.K[k] * n * sin(phase);
        }
        bonded_geometry::write_dihedral_forces(angle, dudphi, force);
        return energy;
    }
};

}  // namespace structmd
