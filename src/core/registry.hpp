#pragma once
// A registry of the components of one kind (pair terms, bonds, integrators, simulation steps, ...):
// the single place where a component's input name ["Class", "SubClass"] meets what implements it.
// Readers, factories, the docs check and the "unknown component" message all iterate it. It is a
// value: the built-in registries are immutable, and a handle that adds components at run time (a
// plugin, an expression) adds them to its own copy, so two handles never see each other's entries.
#include <string>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "core/spelling.hpp"

namespace structmd {

struct ComponentKey {
    std::string cls;       // the input's type[0]
    std::string subclass;  // the input's type[1]

    bool operator==(const ComponentKey& other) const { return cls == other.cls && subclass == other.subclass; }
    std::string text() const { return "[\"" + cls + "\", \"" + subclass + "\"]"; }
};

// Entry: any type with a `ComponentKey key` member.
template <class Entry>
class Registry {
public:
    // Entries keep the order they were added in; a key may be added once.
    void add(Entry entry) {
        if (find(entry.key))
            throw Error(STRUCTMD_ERR_INTERNAL, "component " + entry.key.text() + " is registered twice");
        entries_.push_back(std::move(entry));
    }

    const Entry* find(const ComponentKey& key) const {
        for (const Entry& entry : entries_)
            if (entry.key == key) return &entry;
        return nullptr;
    }

    // The entry of `key`, or an input error at `path` naming the few known components of this kind
    // nearest to it (a registry has over a hundred: the whole list would bury the message).
    const Entry& at(const ComponentKey& key, const std::string& path, const std::string& kind) const {
        if (const Entry* entry = find(key)) return *entry;
        constexpr size_t kSuggestions = 3;
        std::string suggestions;
        for (size_t index : nearest(entries_, kSuggestions, [&](const Entry& entry) {
                 return edit_distance(key.cls, entry.key.cls) + edit_distance(key.subclass, entry.key.subclass);
             }))
            suggestions += (suggestions.empty() ? "" : ", ") + entries_[index].key.text();
        throw input_error(path, "unknown " + kind + " " + key.text() + "; nearest known " + kind + "s: " +
                                    suggestions + " (docs/input-format.md lists them all)");
    }

    const std::vector<Entry>& entries() const { return entries_; }

private:
    std::vector<Entry> entries_;
};

}  // namespace structmd
