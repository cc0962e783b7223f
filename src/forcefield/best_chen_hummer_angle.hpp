#pragma once
// The double-well angle potential of Best, Chen and Hummer (Structure 13, 1755 (2005)) for the
// pseudo-bond angle of C-alpha models, with a helical (alpha) and an extended (beta) minimum:
//   U = -(1/gamma) ln( exp(-gamma [k_a (theta - theta_a)^2 + eps_a]) + exp(-gamma k_b (theta - theta_b)^2) )
// theta the angle at the middle particle r[1] (as HarmonicAngle). Its constants are the paper's,
// in kcal/mol and radians, so the term is defined in KcalMol_A units only:
//   gamma = 0.1 mol/kcal, k_a = 106.4 and k_b = 26.3 kcal/(mol rad^2), theta_a = 1.60 and
//   theta_b = 2.27 rad, eps_a = 4.3 kcal/mol.
// Written as a log-sum-exp about the smaller exponent, U = m - (1/gamma) ln(w_a + w_b) with
// w = exp(-gamma (E - m)) and m = min(E_a, E_b), so that neither exponential underflows; then
// dU/dtheta = (w_a E_a' + w_b E_b') / (w_a + w_b), the two wells' slopes weighted by their weights.
// dU/dtheta does not vanish at theta = 0 or pi: there the force takes the one-sided limit of the
// angle's gradient (bonded_geometry.hpp), as HarmonicAngle does. A zero-length arm gives NaN.
#include "forcefield/bond_potential.hpp"
#include "forcefield/bonded_geometry.hpp"

namespace structmd {

struct BestChenHummerAngle {
    static constexpr int arity = 3;
    static constexpr const char* required_units = "KcalMol_A";

    template <class R>
    struct Params {};

    static std::vector<Parameter> parameters() { return {}; }
    template <class R>
    static Params<R> make_params(const ParameterValues&, const Constants&) {
        return {};
    }

    // U(theta), and dU/dtheta in `slope`.
    template <class R>
    static SMD_HD SMD_INLINE R energy_of_angle(R theta, R& slope) {
        const R gamma = R(0.1);
        const R k_alpha = R(106.4), theta_alpha = R(1.60), eps_alpha = R(4.3);
        const R k_beta = R(26.3), theta_beta = R(2.27);
        const R from_alpha = theta - theta_alpha;
        const R from_beta = theta - theta_beta;
        const R e_alpha = k_alpha * from_alpha * from_alpha + eps_alpha;
        const R e_beta = k_beta * from_beta * from_beta;
        const R least = e_alpha < e_beta ? e_alpha : e_beta;
        const R w_alpha = exp(-gamma * (e_alpha - least));
        const R w_beta = exp(-gamma * (e_beta - least));
        const R total = w_alpha + w_beta;
        slope = (w_alpha * R(2) * k_alpha * from_alpha + w_beta * R(2) * k_beta * from_beta) / total;
        return least - log(total) / gamma;
    }

    template <class R>
    static SMD_HD SMD_INLINE R compute(const Vec3<R>* r, const Params<R>&, const Box<R>&, Vec3<R>* force) {
        const bonded_geometry::BondAngle<R> angle = bonded_geometry::bond_angle(r[0] - r[1], r[2] - r[1]);
        R dudtheta;
        const R energy = energy_of_angle(angle.theta, dudtheta);
        force[0] = (-dudtheta) * angle.dtheta_da;
        force[2] = (-dudtheta) * angle.dtheta_db;
        force[1] = -(force[0] + force[2]);
        return energy;
    }
};

}  // namespace structmd
