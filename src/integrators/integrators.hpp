#pragma once
// The built-in integrators: the one place where an integrator's input name meets its class and its
// inputs. The reader's registry (read_integrators.cpp) and each engine's factories
// (make_integrator.hpp) are both made by visiting this list. A visitor has
//   template <template <class B, class R> class Integrator, class Inputs> void integrator(ComponentKey key);
#include "core/registry.hpp"
#include "integrators/bdhi_cholesky.hpp"
#include "integrators/bdhi_dpstokes.hpp"
#include "integrators/bdhi_fluctuating_immersed_boundary.hpp"
#include "integrators/bdhi_force_coupling.hpp"
#include "integrators/bdhi_lanczos.hpp"
#include "integrators/bdhi_positively_split_ewald.hpp"
#include "integrators/bdhi_quasi2d.hpp"
#include "integrators/brownian.hpp"
#include "integrators/brownian_rigid_body.hpp"
#include "integrators/dpd_verlet.hpp"
#include "integrators/fluctuating_hydrodynamics_compressible_icm.hpp"
#include "integrators/fluctuating_hydrodynamics_icm.hpp"
#include "integrators/langevin_bbk.hpp"
#include "integrators/langevin_gjf.hpp"
#include "integrators/magnetic.hpp"
#include "integrators/magnetic_force_coupling.hpp"
#include "integrators/no_motion.hpp"
#include "integrators/sph_verlet.hpp"
#include "integrators/steepest_descent.hpp"
#include "integrators/velocity_verlet.hpp"

namespace structmd {

template <class Visitor>
void visit_builtin_integrators(Visitor& v) {
    v.template integrator<VelocityVerlet, VelocityVerletInputs>({"Verlet", "VelocityVerlet"});
    v.template integrator<DpdVerlet, DpdVerletInputs>({"DPD", "Verlet"});
    v.template integrator<SphVerlet, SphVerletInputs>({"SPH", "Verlet"});
    v.template integrator<LangevinBBK, LangevinBBKInputs>({"Langevin", "BBK"});
    v.template integrator<LangevinGJF, LangevinInputs>({"Langevin", "GJF"});
    v.template integrator<BrownianEulerMaruyama, BrownianInputs>({"Brownian", "EulerMaruyama"});
    v.template integrator<BrownianEulerMaruyamaRigidBody, BrownianRigidBodyInputs>({"Brownian", "EulerMaruyamaRigidBody"});
    // The same integration: the patches' states change by the patch terms' own rule here, and no patch
    // term of UAMMD-structured defines a probability for the transitions it adds (docs/input-format.md).
    v.template integrator<BrownianEulerMaruyamaRigidBody, BrownianRigidBodyInputs>(
        {"Brownian", "EulerMaruyamaRigidBodyPatchesState"});
    v.template integrator<BdhiCholesky, BdhiOpenBoundaryInputs>({"BDHIOpenBoundary", "Cholesky"});
    v.template integrator<BdhiLanczos, BdhiLanczosInputs>({"BDHIOpenBoundary", "Lanczos"});
    // UAMMD-structured registers it as BDHITriplePeriodic; its documentation says BDHITriplyPeriodic.
    v.template integrator<BdhiForceCoupling, BdhiForceCouplingInputs>({"BDHITriplyPeriodic", "ForceCouplingMethod"});
    v.template integrator<BdhiForceCoupling, BdhiForceCouplingInputs>({"BDHITriplePeriodic", "ForceCouplingMethod"});
    v.template integrator<BdhiQuasi2D, BdhiQuasi2DInputs>({"BDHIDoublyPeriodic", "Quasi2D"});
    v.template integrator<BdhiDPStokes, BdhiDPStokesInputs>({"BDHIDoublyPeriodic", "DPStokes"});
    v.template integrator<BdhiPositivelySplitEwald, BdhiPositivelySplitEwaldInputs>(
        {"BDHITriplyPeriodic", "PositivelySplitEwald"});
    v.template integrator<BdhiPositivelySplitEwald, BdhiPositivelySplitEwaldInputs>(
        {"BDHITriplePeriodic", "PositivelySplitEwald"});
    v.template integrator<IncompressibleInertialCoupling, IcmInputs>(
        {"FluctuatingHydrodynamics", "IncompressibleInertialCoupling"});
    v.template integrator<CompressibleInertialCoupling, CompressibleIcmInputs>(
        {"FluctuatingHydrodynamics", "CompressibleInertialCoupling"});
    v.template integrator<BdhiFluctuatingImmersedBoundary, BdhiFluctuatingImmersedBoundaryInputs>(
        {"BDHITriplyPeriodic", "FluctuatingImmersedBoundary"});
    v.template integrator<BdhiFluctuatingImmersedBoundary, BdhiFluctuatingImmersedBoundaryInputs>(
        {"BDHITriplePeriodic", "FluctuatingImmersedBoundary"});
    v.template integrator<MagneticFixed, MagneticFixedInputs>({"Magnetic", "Fixed"});
    v.template integrator<MagneticBrownian, MagneticBrownianInputs>({"Magnetic", "Brownian"});
    v.template integrator<MagneticForceCoupling, MagneticForceCouplingInputs>({"Magnetic", "ForceCouplingMethod"});
    // The minimiser is also known by the reference's two spellings.
    v.template integrator<SteepestDescent, SteepestDescentInputs>({"SteepestDescent", "SteepestDescent"});
    v.template integrator<SteepestDescent, SteepestDescentInputs>({"Minimization", "SteepestDescent"});
    v.template integrator<SteepestDescent, SteepestDescentInputs>({"Mininimization", "SteepestDescent"});
    v.template integrator<NoMotion, NoMotionInputs>({"None", "None"});
}

}  // namespace structmd
