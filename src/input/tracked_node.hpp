#pragma once
// A read-only view of one JSON value that knows its path in the document and records what was
// read. Reading a key marks it used; check_all_used() then finds the keys nobody read (a misspelt
// parameter, an unknown section) and names them, with a suggestion among the keys that were asked.
#include <array>
#include <cstdint>
#include <initializer_list>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/error.hpp"

namespace structmd::input {

// Shared by every node of one document; owning the document here keeps it alive as long as any node.
struct TrackingState {
    nlohmann::json document;
    // Object path -> its keys in the order the text gives them (nlohmann::json keeps keys sorted).
    std::map<std::string, std::vector<std::string>> keyOrder;
    // Paths of object members read. Array elements need no mark: only object members can be unknown,
    // so check_all_used looks inside a read member only for objects.
    std::set<std::string> used;
    std::map<std::string, std::set<std::string>> asked;  // object path -> keys looked up, present or not
};

class TrackedNode {
public:
    TrackedNode() = default;
    TrackedNode(std::shared_ptr<TrackingState> state, const nlohmann::json* value, std::string path);

    const std::string& path() const { return path_; }
    const nlohmann::json& json() const { return *value_; }
    bool valid() const { return value_ != nullptr; }

    bool is_object() const;
    bool is_array() const;
    bool is_number() const;
    bool is_string() const;

    // Object access. has() and find() record the key as asked; at() throws
    // "<path>.<key>: missing required entry" when absent. All of them mark the returned node used.
    bool has(const std::string& key) const;
    std::optional<TrackedNode> find(const std::string& key) const;
    TrackedNode at(const std::string& key) const;
    std::vector<std::string> keys() const;  // throws "<path>: expected an object" if not one
    // The error for a required key absent from this object: "<path>.<key>: <what>", naming a key of
    // the object nobody asked for that is likely its misspelling ("(found 'timestep': a misspelling
    // of timeStep?)").
    Error missing(const std::string& key, const std::string& what) const;

    // Array access; throws "<path>: expected an array" if not one.
    size_t size() const;
    TrackedNode at(size_t index) const;

    // Typed reads. Throw "<path>: expected <what>, got <json text>" on a type mismatch.
    // Supported T: double, int64_t, int32_t, uint64_t, bool, std::string, std::array<double,3>,
    // std::vector<double>, std::vector<int64_t>.
    template <class T> T as() const;
    template <class T> T get(const std::string& key) const { return at(key).as<T>(); }
    template <class T> T get_or(const std::string& key, T fallback) const {
        auto node = find(key);
        return node ? node->as<T>() : fallback;
    }

    // Marks this node and everything below it as used.
    void mark_used() const;
    // Throws Error(STRUCTMD_ERR_INPUT) for the first key under this node that nobody used:
    // "<path>.<key>: unknown entry (did you mean <closest asked key>?)", or "unknown parameter" when
    // the key sits in a "parameters" object.
    void check_all_used() const;

private:
    std::shared_ptr<TrackingState> state_;
    const nlohmann::json* value_ = nullptr;
    std::string path_;
};

// The labels/data table of a component entry: {"labels": [...], "data": [[...], ...]}.
// read_table checks that every label is known (required or optional), that every required label is
// present, that no label repeats, and that every row has as many cells as there are labels; each
// failure names its path ("<entry>.labels[2]: unknown label 'x' (expected one of a, b)",
// "<entry>.data[5]: row has 3 cells, labels has 4").
class Table {
public:
    Table() = default;
    Table(TrackedNode entry, std::vector<std::string> labels, TrackedNode data);

    size_t rows() const;
    bool has(const std::string& label) const;
    // The cell of a row under a label; the label must be present (has()).
    TrackedNode cell(size_t row, const std::string& label) const;
    TrackedNode row(size_t row) const;

private:
    TrackedNode entry_;
    std::vector<std::string> labels_;
    TrackedNode data_;
};

// Rows with more cells than labels: refused (every table but one), or read without the cells past the
// labels (the state's, which UAMMD-structured's own generators write so and it reads; the caller says so).
enum class TrailingCells { refused, ignored };

Table read_table(const TrackedNode& entry, const std::vector<std::string>& required,
                 const std::vector<std::string>& optional = {}, TrailingCells trailing = TrailingCells::refused);

// The first row of the table with more cells than labels, and how many rows have them; none: count 0.
struct TrailingCellRows {
    size_t count = 0;
    std::string firstPath;
    size_t firstCells = 0;
};
TrailingCellRows rows_with_trailing_cells(const TrackedNode& entry, size_t labels);

}  // namespace structmd::input
