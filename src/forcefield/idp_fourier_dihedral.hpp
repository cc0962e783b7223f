#pragma once
// The dihedral potential of the coarse-grained model of intrinsically disordered proteins of Smith,
// Ho and O'Hern (Phys. Rev. E 90, 042709 (2014)): a Fourier series in the IUPAC dihedral phi of the
// chain r[0]-r[1]-r[2]-r[3] (bonded_geometry.hpp) with the paper's coefficients, in units of k_B T:
//   U = k_B T sum_{s=1..4} [A_s cos(s phi) + B_s sin(s phi)]
//   A = (0.705, -0.313, -0.079, 0.041),   B = (-0.175, -0.093, 0.030, 0.030)
// T is the ensemble's temperature (Constants), read when the force field is made; a changed
// temperature makes the force field again. The sine terms make U odd in part: the sign convention
// of phi matters, and is UAMMD-structured's (the IUPAC one). A chain with three consecutive
// particles collinear has no dihedral: no force, and the energy at phi = 0 (as Dihedral).
#include "forcefield/bond_potential.hpp"
#include "forcefield/bonded_geometry.hpp"

namespace structmd {

struct IdpFourierDihedral {
    static constexpr int arity = 4;

    template <class R>
    struct Params {
        R A[4];  // k_B T A_s, s = 1..4 (energy)
        R B[4];  // k_B T B_s
    };

    static std::vector<Parameter> parameters() { return {}; }
    template <class R>
    static Params<R> make_params(const ParameterValues&, const Constants& c) {
        static constexpr double A[4] = {0.705, -0.313, -0.079, 0.041};
        static constexpr double B[4] = {-0.175, -0.093, 0.030, 0.030};
        Params<R> p;
        for (int s = 0; s < 4; ++s) {
            p.A[s] = R(A[s] * c.kT());
            p.B[s] = R(B[s] * c.kT());
        }
        return p;
    }

    template <class R>
    static SMD_HD SMD_INLINE R compute(const Vec3<R>* r, const Params<R>& p, const Box<R>&, Vec3<R>* force) {
        const bonded_geometry::DihedralAngle<R> angle = bonded_geometry::dihedral_of(r);
        R energy = 0;
        R dudphi = 0;
        for (int k = 0; k < 4; ++k) {
            const R s = R(k + 1);
            const R c = cos(s * angle.phi);
            const R sn = sin(s * angle.phi);
            energy += p.A[k] * c + p.B[k] * sn;
            dudphi += s * (p.B[k] * c - p.A[k] * sn);
        }
        bonded_geometry::write_dihedral_forces(angle, dudphi, force);
        return energy;
    }
};

}  // namespace structmd
