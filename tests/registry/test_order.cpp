// registry.order: a component's parameters reach its functor by name, each in its own role. For every
// force-field registry entry, the spec read from its minimal input is built into interactors with the
// engine's factories (make_interactors, CPU backend, double) and evaluated at two times (fields that
// move depend on time), then:
//  - the same spec with its parameters in another order (a bond's schema permuted and its flat values
//    laid out again to match; the by-name values of pairs and externals inserted in another order)
//    gives bit-identical energies and forces: nothing reads a parameter by its position;
//  - a bond's schema permuted without laying its values out again changes the result: the layout is
//    read through the schema, so a schema out of step with its values would be noticed;
//  - swapping the values of two parameters changes the result, and so does changing any one
//    parameter alone: every name reaches a role, and no two names reach the same one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <vector>

#include "cpu_harness.hpp"
#include "registry_inputs.hpp"

namespace structmd::registry_test {
namespace {

const std::vector<double> kTimes = {0.0, 1.0};

std::vector<ComponentKey> forcefield_keys() { return schema_forcefield_keys(); }

// Every parameter a component reads: per type pair, per bond or per entry, a pair entry's own, and
// an external's per type.
std::vector<Parameter> all_parameters(const ForceFieldComponent& c) {
    std::vector<Parameter> all = c.parameters;
    all.insert(all.end(), c.entryParameters.begin(), c.entryParameters.end());
    all.insert(all.end(), c.typeParameters.begin(), c.typeParameters.end());
    return all;
}

bool holds(const ParameterValues& values, const std::string& name) {
    for (const auto& held : values.all())
        if (held.first == name) return true;
    return false;
}

// The numbers of one parameter wherever the spec's one interaction keeps them: one slot per type-pair
// row, per type row or per bond, or one for the entry.
using Slots = std::vector<std::vector<double>>;

Slots get(const ForceFieldSpec& spec, const std::string& name) {
    Slots slots;
    if (!spec.pairs.empty()) {
        const PairSpec& pair = spec.pairs[0];
        if (holds(pair.shared, name)) return {pair.shared.vector(name)};
        for (const PairSpec::Row& row : pair.rows) slots.push_back(row.values.vector(name));
    } else if (!spec.externals.empty()) {
        const ExternalSpec& external = spec.externals[0];
        if (holds(external.values, name)) return {external.values.vector(name)};
        for (const ExternalSpec::Row& row : external.rows) slots.push_back(row.values.vector(name));
    } else {
        const BondSpec& bonds = spec.bonds.at(0);
        const size_t width = static_cast<size_t>(width_of(bonds.schema));
        for (size_t b = 0; b * width < bonds.values.size(); ++b)
            slots.push_back(values_in_order(bonds.schema, &bonds.values[b * width]).vector(name));
    }
    return slots;
}

void put(ForceFieldSpec& spec, const std::string& name, const Slots& slots) {
    if (!spec.pairs.empty()) {
        PairSpec& pair = spec.pairs[0];
        if (holds(pair.shared, name)) {
            pair.shared.set(name, slots.at(0));
            return;
        }
        for (size_t r = 0; r < pair.rows.size(); ++r) pair.rows[r].values.set(name, slots.at(r));
    } else if (!spec.externals.empty()) {
        ExternalSpec& external = spec.externals[0];
        if (holds(external.values, name)) {
            external.values.set(name, slots.at(0));
            return;
        }
        for (size_t r = 0; r < external.rows.size(); ++r) external.rows[r].values.set(name, slots.at(r));
    } else {
        BondSpec& bonds = spec.bonds.at(0);
        const size_t width = static_cast<size_t>(width_of(bonds.schema));
        size_t offset = 0;
        for (const Parameter& p : bonds.schema) {
            if (name == p.name) break;
            offset += static_cast<size_t>(p.size);
        }
        for (size_t b = 0; b * width < bonds.values.size(); ++b)
            std::copy(slots.at(b).begin(), slots.at(b).end(), bonds.values.begin() + b * width + offset);
    }
}

// `values` with its names inserted in the order `order` gives (a permutation of its indices).
ParameterValues permuted(const ParameterValues& values, const std::vector<size_t>& order) {
    ParameterValues out;
    const auto& all = values.all();
    for (size_t k : order)
        if (k < all.size()) out.set(all[k].first, all[k].second);
    for (const auto& held : all) out.set(held.first, held.second);  // any the order left out, in place
    return out;
}

// The spec with its parameters in the order `order`; a bond's flat values are laid out again to
// match its permuted schema unless `relay` is false.
ForceFieldSpec reorder(ForceFieldSpec spec, const std::vector<size_t>& order, bool relay = true) {
    for (PairSpec& pair : spec.pairs) {
        pair.shared = permuted(pair.shared, order);
        for (PairSpec::Row& row : pair.rows) row.values = permuted(row.values, order);
    }
    for (ExternalSpec& external : spec.externals) {
        external.values = permuted(external.values, order);
        for (ExternalSpec::Row& row : external.rows) row.values = permuted(row.values, order);
    }
    for (BondSpec& bonds : spec.bonds) {
        std::vector<Parameter> schema;
        for (size_t k : order) schema.push_back(bonds.schema.at(k));
        if (relay) {
            std::vector<double> values;
            const size_t width = static_cast<size_t>(width_of(bonds.schema));
            for (size_t b = 0; b * width < bonds.values.size(); ++b) {
                const ParameterValues held = values_in_order(bonds.schema, &bonds.values[b * width]);
                for (const Parameter& p : schema) {
                    const std::vector<double>& numbers = held.vector(p.name);
                    values.insert(values.end(), numbers.begin(), numbers.end());
                }
            }
            bonds.values = values;
        }
        bonds.schema = schema;
    }
    return spec;
}

// The permutations of n items that move something: the reverse and every rotation (a rotation moves
// every item, so a parameter read at a fixed position cannot stay where it was).
std::vector<std::vector<size_t>> orders_of(size_t n) {
    std::vector<std::vector<size_t>> orders;
    std::vector<size_t> identity(n);
    std::iota(identity.begin(), identity.end(), size_t{0});
    std::vector<size_t> reversed(identity.rbegin(), identity.rend());
    orders.push_back(reversed);
    for (size_t shift = 1; shift < n; ++shift) {
        std::vector<size_t> rotated(n);
        for (size_t k = 0; k < n; ++k) rotated[k] = (k + shift) % n;
        if (rotated != reversed) orders.push_back(rotated);
    }
    return orders;
}

bool same_number(double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); }

bool identical(const std::vector<double>& a, const std::vector<double>& b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), same_number);
}

bool finite(const std::vector<double>& a) {
    return std::all_of(a.begin(), a.end(), [](double x) { return std::isfinite(x); });
}

class ParameterOrder : public ::testing::TestWithParam<ComponentKey> {
protected:
    void SetUp() override {
        component_ = forcefield_registry().find(GetParam());
        ASSERT_NE(component_, nullptr);
        scene_ = read_scene(document_with(*component_).dump());
        base_ = evaluate(scene_, scene_.spec, kTimes);
        ASSERT_TRUE(finite(base_)) << "the minimal input gives a non-finite energy or force";
    }

    const ForceFieldComponent* component_ = nullptr;
    Scene scene_;
    std::vector<double> base_;
};

TEST_P(ParameterOrder, AnotherParameterOrderGivesIdenticalResults) {
    const size_t n = std::max({component_->parameters.size(), component_->entryParameters.size(),
                               component_->typeParameters.size()});
    if (n < 2) return;  // nothing to reorder
    for (const std::vector<size_t>& order : orders_of(n)) {
        std::string text;
        for (size_t k : order) text += std::to_string(k) + " ";
        SCOPED_TRACE("order " + text);
        EXPECT_TRUE(identical(evaluate(scene_, reorder(scene_.spec, order), kTimes), base_));
    }
}

TEST_P(ParameterOrder, BondSchemaOutOfStepWithItsValuesIsNoticed) {
    if (component_->kind != InteractionKind::bond || component_->parameters.size() < 2) return;
    for (const std::vector<size_t>& order : orders_of(component_->parameters.size())) {
        std::string text;
        for (size_t k : order) text += std::to_string(k) + " ";
        SCOPED_TRACE("order " + text);
        EXPECT_FALSE(identical(evaluate(scene_, reorder(scene_.spec, order, /*relay=*/false), kTimes), base_));
    }
}

TEST_P(ParameterOrder, SwappingTheValuesOfTwoParametersChangesTheResult) {
    const std::vector<Parameter> all = all_parameters(*component_);
    for (size_t a = 0; a < all.size(); ++a)
        for (size_t b = a + 1; b < all.size(); ++b) {
            const Slots first = get(scene_.spec, all[a].name), second = get(scene_.spec, all[b].name);
            if (all[a].size != all[b].size || first.size() != second.size()) continue;
            SCOPED_TRACE(std::string("swapping ") + all[a].name + " and " + all[b].name);
            ASSERT_NE(first, second) << "the minimal input gives both the same values";
            ForceFieldSpec swapped = scene_.spec;
            put(swapped, all[a].name, second);
            put(swapped, all[b].name, first);
            EXPECT_FALSE(identical(evaluate(scene_, swapped, kTimes), base_));
        }
}

TEST_P(ParameterOrder, EveryParameterChangesTheResultOnItsOwn) {
    for (const Parameter& p : all_parameters(*component_)) {
        SCOPED_TRACE(p.name);
        const Slots given = get(scene_.spec, p.name);
        bool changed = false;
        // Up and down: a bound (a cutoff, a clamp) may act in one direction only.
        for (const auto& change : {+[](double x) { return 1.5 * x + 0.5; }, +[](double x) { return 0.5 * x - 0.5; }}) {
            Slots moved = given;
            for (auto& slot : moved)
                for (double& x : slot) x = change(x);
            ForceFieldSpec other = scene_.spec;
            put(other, p.name, moved);
            const std::vector<double> result = evaluate(scene_, other, kTimes);
            changed = changed || (finite(result) && !identical(result, base_));
        }
        EXPECT_TRUE(changed) << "changing " << p.name << " alone changes no energy, force or torque (finitely)";
    }
}

INSTANTIATE_TEST_SUITE_P(Registry, ParameterOrder, ::testing::ValuesIn(forcefield_keys()),
                         [](const auto& info) { return test_name(info.param); });

}  // namespace
}  // namespace structmd::registry_test
