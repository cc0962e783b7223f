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
#include <cmath>

#include "forcefield/dihedral.hpp"

namespace structmd {

// Each harmonic is Dihedral4's: A cos(s phi) + B sin(s phi) = K [1 + cos(s phi - phi0)] - K with
// K = sqrt(A^2 + B^2) and phi0 = atan2(B, A); the -K add up to the offset.
struct IdpFourierDihedral : Dihedral4 {
    static std::vector<Parameter> parameters() { return {}; }
    template <class R>
    static Params<R> make_params(const ParameterValues&, const Constants& c) {
        static constexpr double A[4] = {0.705, -0.313, -0.079, 0.041};
        static constexpr double B[4] = {-0.175, -0.093, 0.030, 0.030};
        Params<R> p;
        double offset = 0.0;
        for (int s = 0; s < 4; ++s) {
            const double K = std::hypot(A[s], B[s]) * c.kT();
            p.K[s] = R(K);
            p.phi0[s] = R(std::atan2(B[s], A[s]));
            offset -= K;
        }
        p.offset = R(offset);
        return p;
    }
};

}  // namespace structmd
