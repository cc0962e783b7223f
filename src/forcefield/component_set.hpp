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
#include "transverser/transverser_component.hpp"

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

    std::vector<TransverserEntry> transversers;

    // The factories of engine type <B, R, PairR>, created empty on first use.
    template <class B, class R, class PairR>
    Registry<InteractorFactory<B, R>>& factories_to_fill() {
        return slot_to_fill<Registry<InteractorFactory<B, R>>>(factories_, engine_type_key<B, R, PairR>());
    }

    // The factories of engine type <B, R, PairR>, or null when the source was not compiled for it.
    template <class B, class R, class PairR>
    const Registry<InteractorFactory<B, R>>* factories() const {
        return slot<Registry<InteractorFactory<B, R>>>(factories_, engine_type_key<B, R, PairR>());
    }

    // The transverser runners of engine type <B, R, PairR>, as the factories.
    template <class B, class R, class PairR>
    std::vector<TransverserRunner<B, R>>& transverser_runners_to_fill() {
        return slot_to_fill<std::vector<TransverserRunner<B, R>>>(runners_, engine_type_key<B, R, PairR>());
    }

    // The runner of transverser `name` for engine type <B, R, PairR>, or null when the source was
    // not compiled for it.
    template <class B, class R, class PairR>
    const TransverserRunner<B, R>* transverser_runner(const std::string& name) const {
        if (const auto* runners = slot<std::vector<TransverserRunner<B, R>>>(runners_, engine_type_key<B, R, PairR>()))
            for (const TransverserRunner<B, R>& r : *runners)
                if (r.name == name) return &r;
        return nullptr;
    }

private:
    // What one engine type holds of a kind (its factories, its transverser runners).
    struct EngineSlot {
        std::string engineType;
        std::shared_ptr<void> held;
    };

    template <class T>
    static T& slot_to_fill(std::vector<EngineSlot>& slots, const std::string& key) {
        for (EngineSlot& s : slots)
            if (s.engineType == key) return *static_cast<T*>(s.held.get());
        auto held = std::make_shared<T>();
        slots.push_back({key, held});
        return *held;
    }

    template <class T>
    static const T* slot(const std::vector<EngineSlot>& slots, const std::string& key) {
        for (const EngineSlot& s : slots)
            if (s.engineType == key) return static_cast<const T*>(s.held.get());
        return nullptr;
    }

    std::vector<EngineSlot> factories_;  // Registry<InteractorFactory<B, R>> by engine type
    std::vector<EngineSlot> runners_;    // std::vector<TransverserRunner<B, R>> by engine type
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
        for (const TransverserEntry& t : set->transversers)
            if (const ComponentSet* other = transverser_source(t.name))
                throw Error(STRUCTMD_ERR_ARGUMENT, "plugin '" + set->source + "' registers transverser '" + t.name +
                                                       "', which plugin '" + other->source + "' already provides");
        for (const ForceFieldComponent& c : set->reader.entries()) reader_.add(c);
        sets_.push_back(std::move(set));
    }

    // The set that registered transverser `name`, or null.
    const ComponentSet* transverser_source(const std::string& name) const {
        for (const auto& set : sets_)
            for (const TransverserEntry& t : set->transversers)
                if (t.name == name) return set.get();
        return nullptr;
    }

    // The set that registered transverser `name` and its entry; ERR_ARGUMENT naming the known ones
    // when no loaded plugin registered it.
    std::pair<std::shared_ptr<const ComponentSet>, const TransverserEntry*> transverser(const std::string& name) const {
        for (const auto& set : sets_)
            for (const TransverserEntry& t : set->transversers)
                if (t.name == name) return {set, &t};
        throw Error(STRUCTMD_ERR_ARGUMENT, unknown_transverser(name));
    }

    // Why `name` is no transverser: "no transverser named 'X' (the loaded plugins register 'A', 'B'; ...)".
    std::string unknown_transverser(const std::string& name) const {
        std::string known;
        for (const auto& set : sets_)
            for (const TransverserEntry& t : set->transversers) known += (known.empty() ? "'" : ", '") + t.name + "'";
        return "no transverser named '" + name + "' (" +
               (known.empty() ? std::string("no loaded plugin registers one") : "the loaded plugins register " + known) +
               "; docs/plugins.md says how to write one)";
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
