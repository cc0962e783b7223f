#pragma once
// Writing a structmd plugin: a shared library that adds force-field components, used from JSON like
// the built-in ones, and transversers that hosts run by name (docs/plugins.md). A plugin defines its functors against the same contracts as
// the built-ins (forcefield/pair_potential.hpp, bond_potential.hpp, external_potential.hpp) and
// registers them by input name:
//
//   #include "engines/plugin.hpp"
//   struct Buckingham { ... };                                  // a pair functor
//   STRUCTMD_PLUGIN(registrar) {
//       registrar.pair<Buckingham>({"NonBonded", "Buckingham"});
//       registrar.transverser<NeighbourCount>("NeighbourCount");  // transverser_component.hpp
//   }
//
// Registering a component adds its reader entry and its engine factories for every engine type the
// translation unit can build: the CPU backend in single, mixed and double precision always, and the
// CUDA backend too when the plugin is compiled by nvcc (a .cu source) against a library built with
// CUDA. structmd_add_plugin (the installed CMake package) sets up the compiler for all of this.
#include <algorithm>
#include <cstddef>
#include <cstring>
#include <exception>
#include <string>
#include <utility>
#include <vector>

#include "backends/cpu/cpu_backend.hpp"
#include "core/error.hpp"
#include "core/registry.hpp"
#include "engines/plugin_abi.hpp"
#include "forcefield/component_set.hpp"
#include "forcefield/factory_entries.hpp"
#include "forcefield/reader_entries.hpp"
#include "transverser/transverser_component.hpp"
// STRUCTMD_PLUGIN_NO_CUDA: register no CUDA factories even from nvcc (tests the refusal on CUDA).
#if defined(__CUDACC__) && defined(STRUCTMD_HAVE_CUDA) && !defined(STRUCTMD_PLUGIN_NO_CUDA)
#include "backends/cuda/cuda_backend.cuh"
#define STRUCTMD_PLUGIN_HAS_CUDA_FACTORIES 1
#endif

namespace structmd::plugin {

// What a plugin's registration function is given: add components by input name ["Class",
// "SubClass"], with the same calls as the built-in list (forcefield/components.hpp).
class Registrar {
public:
    explicit Registrar(ComponentSet& set) : set_(set) {}

    template <class Potential>
    void pair(ComponentKey key) {
        ReaderEntries{set_.reader}.template pair<Potential>(key);
        each_engine([&](auto& entries) { entries.template pair<Potential>(key); });
    }

    template <class Potential>
    void bond(ComponentKey key, std::vector<std::string> common = {}) {
        ReaderEntries{set_.reader}.template bond<Potential>(key, common);
        each_engine([&](auto& entries) { entries.template bond<Potential>(key, common); });
    }

    template <class Potential>
    void external(ComponentKey key) {
        ReaderEntries{set_.reader}.template external<Potential>(key);
        each_engine([&](auto& entries) { entries.template external<Potential>(key); });
    }

    // A transverser (transverser/transverser_component.hpp) that hosts run by `name` (structmd_traverse).
    template <class T>
    void transverser(const std::string& name) {
        static_assert(T::values >= 1, "a transverser writes at least one number per particle");
        if (name.empty()) throw Error(STRUCTMD_ERR_ARGUMENT, "a transverser needs a name");
        for (const TransverserEntry& t : set_.transversers)
            if (t.name == name) throw Error(STRUCTMD_ERR_ARGUMENT, "transverser '" + name + "' is registered twice");
        set_.transversers.push_back({name, T::parameters(), T::values});
        runner_for<T, CpuBackend, float, float>(name);
        runner_for<T, CpuBackend, double, float>(name);
        runner_for<T, CpuBackend, double, double>(name);
#if defined(STRUCTMD_PLUGIN_HAS_CUDA_FACTORIES)
        runner_for<T, CudaBackend, float, float>(name);
        runner_for<T, CudaBackend, double, float>(name);
        runner_for<T, CudaBackend, double, double>(name);
#endif
    }

private:
    template <class T, class B, class R, class PairR>
    void runner_for(const std::string& name) {
        set_.template transverser_runners_to_fill<B, R, PairR>().push_back({name, &run_transverser<T, B, R>});
    }

    template <class B, class R, class PairR, class Add>
    void add_for(Add& add) {
        FactoryEntries<B, R, PairR, /*WithHessian=*/false> entries;
        add(entries);
        auto& target = set_.template factories_to_fill<B, R, PairR>();
        for (const auto& entry : entries.registry.entries()) target.add(entry);
    }

    template <class Add>
    void each_engine(Add add) {
        add_for<CpuBackend, float, float>(add);
        add_for<CpuBackend, double, float>(add);
        add_for<CpuBackend, double, double>(add);
#if defined(STRUCTMD_PLUGIN_HAS_CUDA_FACTORIES)
        add_for<CudaBackend, float, float>(add);
        add_for<CudaBackend, double, float>(add);
        add_for<CudaBackend, double, double>(add);
#endif
    }

    ComponentSet& set_;
};

// Runs a plugin's registration behind a barrier: no exception leaves the plugin.
template <class Body>
int register_components(ComponentSet* set, char* message, size_t size, Body body) noexcept {
    const auto say = [&](const std::string& text) {
        if (size == 0) return;
        const size_t n = std::min(text.size(), size - 1);
        std::memcpy(message, text.data(), n);
        message[n] = '\0';
    };
    try {
        Registrar registrar(*set);
        body(registrar);
        return STRUCTMD_OK;
    } catch (const Error& e) {
        say(e.what());
        return e.status();
    } catch (const std::exception& e) {
        say(std::string("the plugin's registration failed: ") + e.what());
        return STRUCTMD_ERR_INTERNAL;
    } catch (...) {
        say("the plugin's registration failed with an unknown exception");
        return STRUCTMD_ERR_INTERNAL;
    }
}

}  // namespace structmd::plugin

#define STRUCTMD_PLUGIN_EXPORT extern "C" __attribute__((visibility("default")))

// Defines the plugin's entry points; the block that follows is its registration:
//   STRUCTMD_PLUGIN(registrar) { registrar.pair<MyPotential>({"NonBonded", "Mine"}); }
// Use it once per plugin library.
#define STRUCTMD_PLUGIN(registrar)                                                                                   \
    static void structmd_plugin_components(::structmd::plugin::Registrar& registrar);                                \
    STRUCTMD_PLUGIN_EXPORT int structmd_plugin_abi_version(void) { return STRUCTMD_PLUGIN_ABI_VERSION; }             \
    STRUCTMD_PLUGIN_EXPORT const char* structmd_plugin_build(void) { return STRUCTMD_PLUGIN_BUILD; }                 \
    STRUCTMD_PLUGIN_EXPORT int structmd_plugin_register(::structmd::ComponentSet* set, char* message, size_t size) { \
        return ::structmd::plugin::register_components(set, message, size, &structmd_plugin_components);             \
    }                                                                                                                \
    static void structmd_plugin_components(::structmd::plugin::Registrar& registrar)
