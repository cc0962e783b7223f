#pragma once
// The groups of the built-in force-field components (components.hpp): each engine compiles the
// factories of a group in a translation unit of its own (src/CMakeLists.txt names them one by one),
// so that no unit takes much longer to compile than the others. A pair term instantiates dozens of
// kernels (lists, cluster pairs, all pairs, with and without energy and virial), so the pair terms
// are spread over several groups.
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

// Calls f(std::integral_constant<ComponentGroup, G>{}) for each group, in the order above.
template <class F>
void for_each_component_group(F&& f) {
    using G = ComponentGroup;
    f(std::integral_constant<G, G::lennardJonesPairs>{});
    f(std::integral_constant<G, G::repulsivePairs>{});
    f(std::integral_constant<G, G::chargeAndColloidPairs>{});
    f(std::integral_constant<G, G::softCorePairs>{});
    f(std::integral_constant<G, G::configurablePairs>{});
    f(std::integral_constant<G, G::bondedTerms>{});
    f(std::integral_constant<G, G::externalTerms>{});
}

}  // namespace structmd
