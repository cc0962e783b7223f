#pragma once
// Components added to the built-in force field at run time (a plugin's), and the set a handle reads
// and builds with. A ComponentSet is what one source added: the reader's entries and, per engine type
// it was compiled for, the engine factories. ForceFieldComponents is a handle's value: the built-in
// reader registry plus the sets it loaded, so two handles never see each other's components.
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "core/registry.hpp"
#include "forcefield/component_registry.hpp"
#include "forcefield/forcefield_spec.hpp"
#include "forcefield/interactor_build.hpp"

namespace structmd {

// Names an engine type: the backend and the sizes of R and PairR ("cpu/8/4" is the CPU in mixed
// precision). A factory registry is stored and found under it.
template <class B, class R, class PairR>
std::string engine_type_key() {
    return std::string(B::name) + "/" + std::to_string(sizeof(R)) + "/" + std::to_string(sizeof(PairR));
}

struct ComponentSet {
    std::string source;  // where the components came from (a plugin's path), for messages
    Registry<ForceFieldComponent> reader;

    // The factories of engine type <B, R, PairR>, created empty on first use.
    template <class B, class R, class PairR>
    Registry<InteractorFactory<B, R>>& factories_to_fill() {
        const std::string key = engine_type_key<B, R, PairR>();
        for (EngineFactories& f : factories_)
            if (f.engineType == key) return *static_cast<Registry<InteractorFactory<B, R>>*>(f.registry.get());
        auto registry = std::make_shared<Registry<InteractorFactory<B, R>>>();
        factories_.push_back({key, registry});
        return *registry;
    }

    // The factories of engine type <B, R, PairR>, or null when the source was not compiled for it.
    template <class B, class R, class PairR>
    const Registry<InteractorFactory<B, R>>* factories() const {
        const std::string key = engine_type_key<B, R, PairR>();
        for (const EngineFactories& f : factories_)
            if (f.engineType == key) return static_cast<const Registry<InteractorFactory<B, R>>*>(f.registry.get());
        return nullptr;
    }

private:
    struct EngineFactories {
        std::string engineType;
        std::shared_ptr<void> registry;  // Registry<InteractorFactory<B, R>> of that engine type
    };
    std::vector<EngineFactories> factories_;
};

class ForceFieldComponents {
public:
    // The built-in components alone.
    ForceFieldComponents() : reader_(forcefield_registry()) {}

    // Adds a source's components. A name this set knows already (a built-in's, or another source's)
    // is refused, naming both, and nothing is added.
    void add(std::shared_ptr<const ComponentSet> set) {
        for (const ForceFieldComponent& c : set->reader.entries())
            if (reader_.find(c.key)) {
                const ComponentSet* other = source_of(c.key);
                throw Error(STRUCTMD_ERR_ARGUMENT,
                            "plugin '" + set->source + "' registers " + c.key.text() + ", which " +
                                (other ? "plugin '" + other->source + "'" : std::string("structmd")) +
                                " already provides");
            }
        for (const ForceFieldComponent& c : set->reader.entries()) reader_.add(c);
        sets_.push_back(std::move(set));
    }

    // What the input reader reads with: built-ins, then every added component.
    const Registry<ForceFieldComponent>& reader() const { return reader_; }

    const std::vector<std::shared_ptr<const ComponentSet>>& sets() const { return sets_; }

    // The set that added `key`, or null for a built-in.
    const ComponentSet* source_of(const ComponentKey& key) const {
        for (const auto& set : sets_)
            if (set->reader.find(key)) return set.get();
        return nullptr;
    }

    // What an engine of type <B, R, PairR> builds `spec` with: the built-in factories and those of
    // the added components. A component of `spec` whose source has no factory for this engine type
    // (a plugin built without CUDA on a CUDA handle) is ERR_UNSUPPORTED naming it and the engine.
    template <class B, class R, class PairR>
    Registry<InteractorFactory<B, R>> factories(const Registry<InteractorFactory<B, R>>& builtin,
                                                const ForceFieldSpec& spec, const std::string& precision) const {
        Registry<InteractorFactory<B, R>> all = builtin;
        if (sets_.empty()) return all;
        for (const auto& set : sets_)
            if (const auto* added = set->template factories<B, R, PairR>())
                for (const InteractorFactory<B, R>& f : added->entries()) all.add(f);
        const auto require = [&](const InteractionSpec& s) {
            if (all.find(s.key)) return;
            const ComponentSet* set = source_of(s.key);
            throw Error(STRUCTMD_ERR_UNSUPPORTED,
                        s.path + ": " + s.key.text() + " (from plugin '" + (set ? set->source : std::string("?")) +
                            "') has no implementation for the " + B::name + " backend in " + precision +
                            " precision: that plugin was not compiled for it" +
                            (std::string(B::name) == "cuda" ? " (build it with CUDA, from a .cu source)" : ""));
        };
        for (const auto& s : spec.pairs) require(s);
        for (const auto& s : spec.bonds) require(s);
        for (const auto& s : spec.externals) require(s);
        return all;
    }

private:
    Registry<ForceFieldComponent> reader_;
    std::vector<std::shared_ptr<const ComponentSet>> sets_;
};

}  // namespace structmd
