#pragma once
// The groups of the built-in force-field components (components.hpp): each engine compiles the
// factories of a group in a translation unit of its own (CMakeLists.txt names them one by one, in
// this order, as STRUCTMD_ALL_COMPONENT_GROUPS), so that no unit takes much longer to compile than
// the others. A pair term instantiates dozens of kernels (lists, cluster pairs, all pairs, with and
// without energy and virial), so the pair terms are spread over several groups.
#include <type_traits>

namespace structmd {

enum class ComponentGroup {
    lennardJonesPairs,
    repulsivePairs,
    chargeAndColloidPairs,
    softCorePairs,
    configurablePairs,
    bondedTerms,
    externalTerms
};

// The groups this build compiles (CMake's STRUCTMD_COMPONENT_GROUPS), bit i for the i-th group above:
// every group unless a build for a benchmark alone leaves some out. A component of a group left out
// is neither read nor built, so an input naming it is refused as unknown.
#ifndef STRUCTMD_COMPONENT_GROUPS_BUILT
#define STRUCTMD_COMPONENT_GROUPS_BUILT 0x7f
#endif
constexpr bool component_group_built(ComponentGroup g) {
    return ((STRUCTMD_COMPONENT_GROUPS_BUILT) >> static_cast<int>(g) & 1) != 0;
}

// Calls f(std::integral_constant<ComponentGroup, G>{}) for each group built, in the order above.
template <class F>
void for_each_component_group(F&& f) {
    using G = ComponentGroup;
    const auto built = [&f](auto group) {
        if constexpr (component_group_built(decltype(group)::value)) f(group);
    };
    built(std::integral_constant<G, G::lennardJonesPairs>{});
    built(std::integral_constant<G, G::repulsivePairs>{});
    built(std::integral_constant<G, G::chargeAndColloidPairs>{});
    built(std::integral_constant<G, G::softCorePairs>{});
    built(std::integral_constant<G, G::configurablePairs>{});
    built(std::integral_constant<G, G::bondedTerms>{});
    built(std::integral_constant<G, G::externalTerms>{});
}

}  // namespace structmd
