#pragma once
// The built-in force-field components: the one place where an input name ["Class", "SubClass"]
// meets the functor that computes it. The reader's registry (component_registry.cpp: parameter
// schemas, tables) and each engine's factories (make_interactors.hpp) are both made by visiting this
// list, so a new potential is its functor file plus one line here, in the group of its kind
// (component_groups.hpp: each group is compiled in a unit of its own).
//
// A visitor has
//   template <class Potential> void pair(ComponentKey key);   // NonBonded, over a Verlet list or all pairs
//   template <class Potential> void bond(ComponentKey key, std::vector<std::string> common = {});
//   template <class Potential> void external(ComponentKey key);   // External and Surface entries
//   template <class Component> void configurable(ComponentKey key);
// `common` names the bond parameters given once in the entry's "parameters" for every bond (the
// Common_ variants) rather than as table columns. A configurable component (an expression, a
// table: its parameters depend on its entry) has
//   static ForceFieldComponent reader_entry(ComponentKey key);   // with configure() set
//   template <class B, class R, class PairR>
//   static std::unique_ptr<Interactor<B, R>> make_interactor(const InteractorBuild<B, R>&,
//                                                            const InteractionSpec&);
// and reads its own ComponentConfig from the spec.
#include <string>
#include <vector>

#include "core/registry.hpp"
#include "forcefield/component_groups.hpp"
#include "forcefield/absorbed.hpp"
#include "forcefield/afm_conic_tip.hpp"
#include "forcefield/afm_tip.hpp"
#include "forcefield/best_chen_hummer_angle.hpp"
#include "forcefield/clashed.hpp"
#include "forcefield/constant_force_bond.hpp"
#include "forcefield/constant_torque.hpp"
#include "forcefield/coulomb.hpp"
#include "forcefield/debye_huckel.hpp"
#include "forcefield/dihedral.hpp"
#include "forcefield/dipolar_magnetic.hpp"
#include "forcefield/dlvo.hpp"
#include "forcefield/electrostatics.hpp"
#include "forcefield/expression_component.hpp"
#include "forcefield/external_constant_force.hpp"
#include "forcefield/fene_bond.hpp"
#include "forcefield/fixed_harmonic.hpp"
#include "forcefield/flat_surfaces.hpp"
#include "forcefield/gaussian_bond.hpp"
#include "forcefield/gravity.hpp"
#include "forcefield/harmonic_angle.hpp"
#include "forcefield/harmonic_anisotropic.hpp"
#include "forcefield/harmonic_bond.hpp"
#include "forcefield/idp_fourier_dihedral.hpp"
#include "forcefield/kim_hummer.hpp"
#include "forcefield/kratky_porod.hpp"
#include "forcefield/la_torre.hpp"
#include "forcefield/magnetic_field.hpp"
#include "forcefield/lambda_harmonic.hpp"
#include "forcefield/lennard_jones.hpp"
#include "forcefield/lennard_jones_general.hpp"
#include "forcefield/lennard_jones_wca.hpp"
#include "forcefield/max_distance_restraint.hpp"
#include "forcefield/patchy_particles.hpp"
#include "forcefield/morse.hpp"
#include "forcefield/plain_cylinder.hpp"
#include "forcefield/plates.hpp"
#include "forcefield/rotational_alignment.hpp"
#include "forcefield/soft_core.hpp"
#include "forcefield/set_interaction.hpp"
#include "forcefield/spherical_shell.hpp"
#include "forcefield/split_lennard_jones.hpp"
#include "forcefield/steric.hpp"
#include "forcefield/steric_inner.hpp"
#include "forcefield/tabulated.hpp"
#include "forcefield/tabulated_field.hpp"
#include "forcefield/wca_core_wells.hpp"
#include "forcefield/wca_polyhedron.hpp"
#include "forcefield/zhang.hpp"

namespace structmd {

// The Lennard-Jones forms of the NonBonded pair terms.
template <class Visitor>
void visit_lennard_jones_pairs(Visitor& v) {
    v.template pair<LennardJonesType1>({"NonBonded", "LennardJonesType1"});
    v.template pair<LennardJonesType2>({"NonBonded", "LennardJonesType2"});
    v.template pair<LennardJonesType3>({"NonBonded", "LennardJonesType3"});
    v.template pair<GeneralLennardJonesType1>({"NonBonded", "GeneralLennardJonesType1"});
    v.template pair<GeneralLennardJonesType2>({"NonBonded", "GeneralLennardJonesType2"});
    v.template pair<GeneralLennardJonesType3>({"NonBonded", "GeneralLennardJonesType3"});
    v.template pair<SplitLennardJones>({"NonBonded", "SplitLennardJones"});
}

// The purely repulsive NonBonded pair terms.
template <class Visitor>
void visit_repulsive_pairs(Visitor& v) {
    v.template pair<WCAType1>({"NonBonded", "WCAType1"});
    v.template pair<WCAType2>({"NonBonded", "WCAType2"});
    v.template pair<WCAType3>({"NonBonded", "WCAType3"});
    v.template pair<Steric6>({"NonBonded", "Steric6"});
    v.template pair<Steric12>({"NonBonded", "Steric12"});
    v.template pair<Clashed>({"NonBonded", "Clashed"});
}

// The NonBonded pair terms of charges, masses and colloids, and the membrane tail.
template <class Visitor>
void visit_charge_and_colloid_pairs(Visitor& v) {
    v.template pair<DebyeHuckel>({"NonBonded", "DebyeHuckel"});
    v.template pair<Coulomb>({"NonBonded", "Coulomb"});
    v.template pair<Gravity>({"NonBonded", "Gravity"});
    v.template pair<LaTorre>({"NonBonded", "LaTorre"});
    v.template pair<DLVOType1>({"NonBonded", "DLVOType1"});
    v.template pair<DLVOType2>({"NonBonded", "DLVOType2"});
    v.template pair<DLVOType3>({"NonBonded", "DLVOType3"});
    v.template pair<KimHummer>({"NonBonded", "KimHummer"});
}

// The NonBonded soft cores of alchemical (lambda) runs.
template <class Visitor>
void visit_soft_core_pairs(Visitor& v) {
    v.template pair<Steric6SoftCore>({"NonBonded", "Steric6SoftCore"});
    v.template pair<Steric12SoftCore>({"NonBonded", "Steric12SoftCore"});
    v.template pair<LennardJonesSoftCoreType1>({"NonBonded", "LennardJonesSoftCoreType1"});
    v.template pair<LennardJonesSoftCoreType2>({"NonBonded", "LennardJonesSoftCoreType2"});
}

// The pair terms configured by their entries: tables, expressions, long-range electrostatics, patches.
template <class Visitor>
void visit_configurable_pairs(Visitor& v) {
    v.template configurable<StericInnerComponent<6>>({"NonBonded", "StericInner6"});
    v.template configurable<StericInnerComponent<12>>({"NonBonded", "StericInner12"});
    v.template configurable<ZhangComponent>({"NonBonded", "Zhang"});
    v.template configurable<TabulatedPair>({"NonBonded", "Tabulated"});

    v.template configurable<Electrostatics>({"LongRange", "Electrostatics"});

    v.template configurable<DipolarMagnetic>({"NonBonded", "DipolarMagnetic"});

    v.template configurable<PatchyParticlesComponent>({"PatchyParticles", "PatchyParticles"});
    v.template configurable<PatchyParticlesComponent>({"PatchyParticles", "DynamicallyBondedPatchyParticles"});

    v.template configurable<ExpressionPairComponent>({"NonBonded", "Expression"});
}

// The bonds, angles and dihedrals (Bond1 to Bond4).
template <class Visitor>
void visit_bonded_terms(Visitor& v) {
    v.template bond<FixedHarmonic>({"Bond1", "FixedHarmonic"});
    v.template bond<ConstantForceBond>({"Bond1", "ConstantForce"});
    v.template bond<FixedHarmonicAnisotropic>({"Bond1", "FixedHarmonicAnisotropic"});
    v.template bond<LambdaFixedHarmonicAnisotropic>({"Bond1", "LambdaFixedHarmonicAnisotropic"}, {"n"});
    using Harmonic = RadialBond<HarmonicBond>;

    v.template bond<Harmonic>({"Bond2", "Harmonic"});
    v.template bond<Harmonic>({"Bond2", "HarmonicCommon_K"}, {"K"});
    v.template bond<Harmonic>({"Bond2", "HarmonicCommon_K_r0"}, {"K", "r0"});
    using Fene = RadialBond<FeneBond>;
    v.template bond<Fene>({"Bond2", "Fene"});
    v.template bond<Fene>({"Bond2", "FeneCommon_K_R0"}, {"K", "R0"});
    v.template bond<Fene>({"Bond2", "FeneCommon_r0_K_R0"}, {"r0", "K", "R0"});
    using Morse = RadialBond<MorseBond>;
    v.template bond<Morse>({"Bond2", "Morse"});
    v.template bond<Morse>({"Bond2", "MorseCommon_D"}, {"D"});
    v.template bond<Morse>({"Bond2", "MorseCommon_r0_E_D"}, {"r0", "E", "D"});
    v.template bond<RadialBond<LennardJonesType1>>({"Bond2", "LennardJonesType1"});
    v.template bond<RadialBond<LennardJonesType1>>({"Bond2", "LennardJonesType1Common_epsilon"}, {"epsilon"});
    v.template bond<RadialBond<LennardJonesType2>>({"Bond2", "LennardJonesType2"});
    v.template bond<RadialBond<LennardJonesType2>>({"Bond2", "LennardJonesType2Common_epsilon"}, {"epsilon"});
    v.template bond<RadialBond<LennardJonesType3>>({"Bond2", "LennardJonesType3"});
    v.template bond<RadialBond<LennardJonesType3>>({"Bond2", "LennardJonesType3Common_epsilon"}, {"epsilon"});
    using Gaussian = RadialBond<GaussianBond>;
    v.template bond<Gaussian>({"Bond2", "Gaussian"});
    v.template bond<Gaussian>({"Bond2", "GaussianCommon_E_r0_D"}, {"E", "r0", "D"});
    v.template bond<RadialBond<Steric6>>({"Bond2", "Steric6"});
    v.template bond<RadialBond<Steric6>>({"Bond2", "Steric6Common_epsilon_sigma"}, {"epsilon", "sigma"});
    v.template bond<RadialBond<Steric12>>({"Bond2", "Steric12"});
    v.template bond<RadialBond<Steric12>>({"Bond2", "Steric12Common_epsilon_sigma"}, {"epsilon", "sigma"});
    v.template bond<RadialBond<DebyeHuckel>>({"Bond2", "DebyeHuckel"});
    v.template bond<RadialBond<LennardJonesKaranicolasBrooks>>({"Bond2", "LennardJonesKaranicolasBrooks"});
    v.template bond<RadialBond<LennardJonesKaranicolasBrooks>>({"Bond2", "LennardJonesKaranicolasBrooksCommon_epsilon"},
                                                               {"epsilon"});
    v.template bond<RadialBond<LennardJonesGaussianBond>>({"Bond2", "LennardJonesGaussian"});
    v.template bond<RadialBond<LennardJonesGaussianBond>>({"Bond2", "LennardJonesGaussianCommon_epsilon_D"},
                                                          {"epsilon", "D"});
    v.template bond<RadialBond<MorseWCABond>>({"Bond2", "MorseWCACommon_eps0"}, {"eps0"});
    v.template bond<RadialBond<MaxDistanceRestraint>>({"Bond2", "MaxDistanceRestraint"});
    v.template bond<HarmonicAnisotropicBond>({"Bond2", "HarmonicAnisotropic"});
    v.template configurable<TabulatedBond>({"Bond2", "Tabulated"});
    v.template configurable<OrientedBondComponent<RAPPotential>>({"Bond2", "RAP"});
    v.template configurable<OrientedBondComponent<HarmonicRAPPotential>>({"Bond2", "HarmonicRAP"});
    v.template bond<RadialLambdaBond<LambdaHarmonicBond>>({"Bond2", "LambdaHarmonic"}, {"n"});
    using SoftCoreBond1 = RadialLambdaBond<LennardJonesSoftCoreType1>;
    v.template bond<SoftCoreBond1>({"Bond2", "LennardJonesSoftCoreType1"}, {"alpha", "n"});
    v.template bond<SoftCoreBond1>({"Bond2", "LennardJonesSoftCoreType1Common_epsilon"}, {"epsilon", "alpha", "n"});
    using SoftCoreBond2 = RadialLambdaBond<LennardJonesSoftCoreType2>;
    v.template bond<SoftCoreBond2>({"Bond2", "LennardJonesSoftCoreType2"}, {"alpha", "n"});
    v.template bond<SoftCoreBond2>({"Bond2", "LennardJonesSoftCoreType2Common_epsilon"}, {"epsilon", "alpha", "n"});

    v.template bond<HarmonicAngle>({"Bond3", "HarmonicAngular"});
    v.template bond<HarmonicAngle>({"Bond3", "HarmonicAngularCommon_K"}, {"K"});
    v.template bond<HarmonicAngle>({"Bond3", "HarmonicAngularCommon_K_theta0"}, {"K", "theta0"});
    v.template bond<KratkyPorod>({"Bond3", "KratkyPorod"});
    v.template bond<KratkyPorod>({"Bond3", "KratkyPorodCommon_K"}, {"K"});
    v.template bond<BestChenHummerAngle>({"Bond3", "BestChenHummerAngular"});
    v.template configurable<TabulatedAngle>({"Bond3", "Tabulated"});

    v.template bond<Dihedral>({"Bond4", "Dihedral"});
    v.template bond<Dihedral>({"Bond4", "DihedralCommon_n_K_phi0"}, {"n", "K", "phi0"});
    v.template bond<Dihedral4>({"Bond4", "Dihedral4"});
    v.template bond<IdpFourierDihedral>({"Bond4", "IDP_Fourier"});
    v.template configurable<TabulatedDihedral>({"Bond4", "Tabulated"});

    v.template configurable<ExpressionBondComponent<2>>({"Bond2", "Expression"});

    v.template configurable<ExpressionBondComponent<3>>({"Bond3", "Expression"});

    v.template configurable<ExpressionBondComponent<4>>({"Bond4", "Expression"});
}

// The terms of one particle (External, Surface), of sets of particles (Set1, Set2) and the AFM tips.
template <class Visitor>
void visit_external_terms(Visitor& v) {
    v.template external<ExternalConstantForce>({"External", "ConstantForce"});
    v.template configurable<ConstantTorqueComponent>({"External", "ConstantTorque"});
    v.template configurable<ConstantMagneticField>({"External", "ConstantMagneticField"});
    v.template configurable<ACMagneticField>({"External", "ACMagneticField"});
    v.template external<Plates>({"External", "Plates"});
    v.template external<SphericalShell>({"External", "SphericalShell"});
    v.template configurable<TabulatedFieldComponent<false>>({"External", "ExternalTabulated"});
    v.template configurable<TabulatedFieldComponent<true>>({"External", "PolarizationTabulated"});
    v.template configurable<HelixBoundariesComponent>({"External", "HelixBoundaries"});

    v.template external<SurfaceLennardJonesType1>({"Surface", "SurfaceLennardJonesType1"});
    v.template external<SurfaceLennardJonesType2>({"Surface", "SurfaceLennardJonesType2"});
    v.template external<SurfaceWCAType1>({"Surface", "SurfaceWCAType1"});
    v.template external<SurfaceWCAType2>({"Surface", "SurfaceWCAType2"});
    v.template external<SurfaceGeneralLennardJonesType1>({"Surface", "SurfaceGeneralLennardJonesType1"});
    v.template external<SurfaceGeneralLennardJonesType2>({"Surface", "SurfaceGeneralLennardJonesType2"});
    v.template external<SurfaceIntegratedLennardJonesType2>({"Surface", "SurfaceIntegratedLennardJonesType2"});
    v.template external<SurfaceAnchorage>({"Surface", "SurfaceAnchorage"});
    v.template external<ParabolaSurface>({"Surface", "ParabolaSurface"});
    v.template external<WCAPlainCylinder>({"Surface", "WCA_PlainCylinder"});
    v.template configurable<WCAPolyhedron>({"Surface", "WCA_Polyhedron"});
    v.template configurable<AbsorbedComponent>({"Surface", "Absorbed"});

    v.template configurable<SetComponent<ConstantForceBond>>({"Set1", "ConstantForceOverCenterOfMass"});
    v.template configurable<SetComponent<FixedHarmonicAnisotropic>>({"Set1", "FixedHarmonicAnisotropicCenterOfMass"});
    v.template configurable<SetComponent<FixedHarmonicIsotropicCommon>>(
        {"Set1", "FixedHarmonicAnisotropicCommon_K_r0CenterOfMass"});
    v.template configurable<SetComponent<ConstantTorqueOnSet>>({"Set1", "ConstantTorqueOverCenterOfMass"});

    v.template configurable<SetComponent<RadialBond<ConstantForceRadial>>>(
        {"Set2", "ConstantForceBetweenCentersOfMass"});
    v.template configurable<SetComponent<RadialBond<HarmonicBond>>>({"Set2", "HarmonicBondBetweenCentersOfMass"});
    v.template configurable<SetComponent<ConstantTorqueBetweenSets>>({"Set2", "ConstantTorqueBetweenCentersOfMass"});

    v.template configurable<AfmComponent<SphericalTipPotential>>({"AFM", "SphericalTip"});
    v.template configurable<AfmComponent<SphericallyBluntedConicTipPotential>>({"AFM", "SphericallyBluntedConicTip"});

    v.template configurable<ExpressionExternalComponent>({"External", "Expression"});
}

// The calls of one group (component_groups.hpp): each is compiled into an engine unit of its own.
template <ComponentGroup G, class Visitor>
void visit_component_group(Visitor& v) {
    if constexpr (G == ComponentGroup::lennardJonesPairs) {
        visit_lennard_jones_pairs(v);
    } else if constexpr (G == ComponentGroup::repulsivePairs) {
        visit_repulsive_pairs(v);
    } else if constexpr (G == ComponentGroup::chargeAndColloidPairs) {
        visit_charge_and_colloid_pairs(v);
    } else if constexpr (G == ComponentGroup::softCorePairs) {
        visit_soft_core_pairs(v);
    } else if constexpr (G == ComponentGroup::configurablePairs) {
        visit_configurable_pairs(v);
    } else if constexpr (G == ComponentGroup::bondedTerms) {
        visit_bonded_terms(v);
    } else {
        static_assert(G == ComponentGroup::externalTerms, "a component group without its visit");
        visit_external_terms(v);
    }
}

template <class Visitor>
void visit_builtin_forcefield(Visitor& v) {
    for_each_component_group([&v](auto group) { visit_component_group<decltype(group)::value>(v); });
}

}  // namespace structmd
