#include "input/tracked_node.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "core/spelling.hpp"

namespace structmd::input {
namespace {

using nlohmann::json;

std::string member_path(const std::string& parent, const std::string& key) {
    return parent.empty() ? key : parent + "." + key;
}

std::string element_path(const std::string& parent, size_t index) {
    return parent + "[" + std::to_string(index) + "]";
}

std::string join(const std::vector<std::string>& words) {
    std::string text;
    for (const std::string& word : words) text += (text.empty() ? "" : ", ") + word;
    return text;
}

// The value as written, shortened so that a message stays on one line.
std::string excerpt(const json& value) {
    constexpr size_t kMaxChars = 60;
    std::string text = value.dump();
    if (text.size() > kMaxChars) text = text.substr(0, kMaxChars - 3) + "...";
    return text;
}

[[noreturn]] void throw_expected(const TrackedNode& node, const std::string& what) {
    throw input_error(node.path(), "expected " + what + ", got " + excerpt(node.json()));
}

// A default-constructed node points nowhere; reading through it is a bug in the caller.
void require_value(const TrackedNode& node) {
    if (!node.valid()) throw Error(STRUCTMD_ERR_INTERNAL, node.path() + ": read through an empty TrackedNode");
}

void require_object(const TrackedNode& node) {
    require_value(node);
    if (!node.is_object()) throw_expected(node, "an object");
}

void require_array(const TrackedNode& node) {
    require_value(node);
    if (!node.is_array()) throw_expected(node, "an array");
}

std::vector<std::string> ordered_keys(const TrackingState& state, const std::string& path, const json& object) {
    auto recorded = state.keyOrder.find(path);
    if (recorded != state.keyOrder.end() && recorded->second.size() == object.size()) return recorded->second;
    std::vector<std::string> keys;
    for (const auto& item : object.items()) keys.push_back(item.key());
    return keys;
}

// Keys of a component's "parameters" object, or of an object of parameters named so
// ("transverserParameters": a plugin transverser's), are reported as parameters, the word users know
// them by.
bool is_parameters_object(const std::string& path) {
    const std::string name = "parameters", named = "Parameters";
    if (path == name) return true;
    if (path.size() > named.size() && path.compare(path.size() - named.size(), std::string::npos, named) == 0)
        return true;
    return path.size() > name.size() && path.compare(path.size() - name.size() - 1, std::string::npos, "." + name) == 0;
}

Error unknown_member(const TrackingState& state, const std::string& objectPath, const std::string& key,
                     const json& object) {
    std::string what = is_parameters_object(objectPath) ? "unknown parameter" : "unknown entry";
    auto asked = state.asked.find(objectPath);
    if (asked != state.asked.end()) {
        const std::vector<std::string> known(asked->second.begin(), asked->second.end());
        std::vector<std::string> absent;
        for (const std::string& candidate : known)
            if (!object.contains(candidate)) absent.push_back(candidate);
        if (auto suggestion = closest(key, absent))
            what += " (did you mean " + *suggestion + "?)";
        else
            what += " (known here: " + join(known) + ")";
    }
    return input_error(member_path(objectPath, key), what);
}

// Walks below value (at path, used as a scratch buffer and restored) for an object member never read.
void check_used_below(const TrackingState& state, const json& value, std::string& path) {
    const size_t parentLength = path.size();
    if (value.is_object()) {
        const std::string objectPath = path;
        for (const std::string& key : ordered_keys(state, objectPath, value)) {
            if (!path.empty()) path += '.';
            path += key;
            if (state.used.count(path) == 0) throw unknown_member(state, objectPath, key, value);
            check_used_below(state, value.at(key), path);
            path.resize(parentLength);
        }
    } else if (value.is_array()) {
        for (size_t i = 0; i < value.size(); ++i) {
            if (!value[i].is_structured()) continue;
            path += "[" + std::to_string(i) + "]";
            check_used_below(state, value[i], path);
            path.resize(parentLength);
        }
    }
}

void mark_used_below(TrackingState& state, const json& value, std::string& path) {
    const size_t parentLength = path.size();
    if (value.is_object()) {
        for (const auto& item : value.items()) {
            if (!path.empty()) path += '.';
            path += item.key();
            state.used.insert(path);
            mark_used_below(state, item.value(), path);
            path.resize(parentLength);
        }
    } else if (value.is_array()) {
        for (size_t i = 0; i < value.size(); ++i) {
            if (!value[i].is_structured()) continue;
            path += "[" + std::to_string(i) + "]";
            mark_used_below(state, value[i], path);
            path.resize(parentLength);
        }
    }
}

// Integers may be written 3 or 3.0 (writers that pass through floating point), never 3.5.
int64_t read_integer(const TrackedNode& node, int64_t lowest, int64_t highest, const std::string& what) {
    require_value(node);
    const json& value = node.json();
    if (value.is_number_unsigned()) {
        const uint64_t number = value.get<uint64_t>();
        if (number > static_cast<uint64_t>(highest)) throw_expected(node, what);
        return static_cast<int64_t>(number);
    }
    if (value.is_number_integer()) {
        const int64_t number = value.get<int64_t>();
        if (number < lowest || number > highest) throw_expected(node, what);
        return number;
    }
    if (value.is_number_float()) {
        const double number = value.get<double>();
        constexpr double kTwoTo63 = 9223372036854775808.0;  // exact in a double; int64_t stops just below
        const bool fits = number >= static_cast<double>(lowest) && number < kTwoTo63 &&
                          static_cast<int64_t>(number) <= highest;
        if (std::floor(number) != number || !fits) throw_expected(node, what);
        return static_cast<int64_t>(number);
    }
    throw_expected(node, what);
}

// Per-type readers behind TrackedNode::as<T>().
template <class T> struct Reader;

template <> struct Reader<double> {
    static double read(const TrackedNode& node) {
        require_value(node);
        if (!node.is_number()) throw_expected(node, "a number");
        return node.json().get<double>();
    }
};

template <> struct Reader<int64_t> {
    static int64_t read(const TrackedNode& node) {
        return read_integer(node, std::numeric_limits<int64_t>::min(), std::numeric_limits<int64_t>::max(),
                            "an integer");
    }
};

template <> struct Reader<int32_t> {
    static int32_t read(const TrackedNode& node) {
        return static_cast<int32_t>(read_integer(node, std::numeric_limits<int32_t>::min(),
                                                 std::numeric_limits<int32_t>::max(), "a 32-bit integer"));
    }
};

template <> struct Reader<uint64_t> {
    static uint64_t read(const TrackedNode& node) {
        require_value(node);
        if (node.json().is_number_unsigned()) return node.json().get<uint64_t>();
        return static_cast<uint64_t>(
            read_integer(node, 0, std::numeric_limits<int64_t>::max(), "a non-negative integer"));
    }
};

template <> struct Reader<bool> {
    static bool read(const TrackedNode& node) {
        require_value(node);
        if (!node.json().is_boolean()) throw_expected(node, "true or false");
        return node.json().get<bool>();
    }
};

template <> struct Reader<std::string> {
    static std::string read(const TrackedNode& node) {
        require_value(node);
        if (!node.is_string()) throw_expected(node, "a string");
        return node.json().get<std::string>();
    }
};

// Element by element through json directly; a node per element is built only to name a bad one.
template <> struct Reader<std::vector<double>> {
    static std::vector<double> read(const TrackedNode& node) {
        require_value(node);
        if (!node.is_array()) throw_expected(node, "a list of numbers");
        std::vector<double> numbers;
        numbers.reserve(node.json().size());
        for (size_t i = 0; i < node.json().size(); ++i) {
            const json& element = node.json()[i];
            numbers.push_back(element.is_number() ? element.get<double>() : node.at(i).as<double>());
        }
        return numbers;
    }
};

template <> struct Reader<std::array<double, 3>> {
    static std::array<double, 3> read(const TrackedNode& node) {
        require_value(node);
        if (!node.is_array() || node.json().size() != 3) throw_expected(node, "[x, y, z] (3 numbers)");
        const std::vector<double> numbers = Reader<std::vector<double>>::read(node);
        return {numbers[0], numbers[1], numbers[2]};
    }
};

template <> struct Reader<std::vector<int64_t>> {
    static std::vector<int64_t> read(const TrackedNode& node) {
        require_value(node);
        if (!node.is_array()) throw_expected(node, "a list of integers");
        std::vector<int64_t> numbers;
        numbers.reserve(node.json().size());
        for (size_t i = 0; i < node.json().size(); ++i) {
            const json& element = node.json()[i];
            const bool fits = element.is_number_integer() &&
                              (!element.is_number_unsigned() ||
                               element.get<uint64_t>() <= static_cast<uint64_t>(std::numeric_limits<int64_t>::max()));
            numbers.push_back(fits ? element.get<int64_t>() : node.at(i).as<int64_t>());
        }
        return numbers;
    }
};

}  // namespace

TrackedNode::TrackedNode(std::shared_ptr<TrackingState> state, const nlohmann::json* value, std::string path)
    : state_(state ? std::move(state) : std::make_shared<TrackingState>()), value_(value), path_(std::move(path)) {}

bool TrackedNode::is_object() const { return value_ && value_->is_object(); }
bool TrackedNode::is_array() const { return value_ && value_->is_array(); }
bool TrackedNode::is_number() const { return value_ && value_->is_number(); }
bool TrackedNode::is_string() const { return value_ && value_->is_string(); }

bool TrackedNode::has(const std::string& key) const {
    require_object(*this);
    state_->asked[path_].insert(key);
    return value_->contains(key);
}

std::optional<TrackedNode> TrackedNode::find(const std::string& key) const {
    require_object(*this);
    state_->asked[path_].insert(key);
    auto member = value_->find(key);
    if (member == value_->end()) return std::nullopt;
    std::string childPath = member_path(path_, key);
    state_->used.insert(childPath);
    return TrackedNode(state_, &*member, std::move(childPath));
}

TrackedNode TrackedNode::at(const std::string& key) const {
    auto member = find(key);
    if (!member) throw missing(key, "missing required entry");
    return *member;
}

Error TrackedNode::missing(const std::string& key, const std::string& what) const {
    require_object(*this);
    // A key nobody asked for is no other entry's spelling, so it may be this one's.
    const std::set<std::string>& asked = state_->asked[path_];
    std::vector<std::string> unasked;
    for (const std::string& present : ordered_keys(*state_, path_, *value_))
        if (asked.count(present) == 0) unasked.push_back(present);
    const std::optional<std::string> misspelt = closest(key, unasked);
    return input_error(member_path(path_, key),
                       misspelt ? what + " (found '" + *misspelt + "': a misspelling of " + key + "?)" : what);
}

std::vector<std::string> TrackedNode::keys() const {
    require_object(*this);
    return ordered_keys(*state_, path_, *value_);
}

size_t TrackedNode::size() const {
    require_array(*this);
    return value_->size();
}

TrackedNode TrackedNode::at(size_t index) const {
    require_array(*this);
    if (index >= value_->size())
        throw input_error(element_path(path_, index),
                          "missing (the list has " + std::to_string(value_->size()) + " entries)");
    return TrackedNode(state_, &(*value_)[index], element_path(path_, index));
}

template <class T> T TrackedNode::as() const { return Reader<T>::read(*this); }

template double TrackedNode::as<double>() const;
template int64_t TrackedNode::as<int64_t>() const;
template int32_t TrackedNode::as<int32_t>() const;
template uint64_t TrackedNode::as<uint64_t>() const;
template bool TrackedNode::as<bool>() const;
template std::string TrackedNode::as<std::string>() const;
template std::array<double, 3> TrackedNode::as<std::array<double, 3>>() const;
template std::vector<double> TrackedNode::as<std::vector<double>>() const;
template std::vector<int64_t> TrackedNode::as<std::vector<int64_t>>() const;

void TrackedNode::mark_used() const {
    if (!value_) return;
    if (!path_.empty()) state_->used.insert(path_);
    std::string path = path_;
    mark_used_below(*state_, *value_, path);
}

void TrackedNode::check_all_used() const {
    if (!value_) return;
    std::string path = path_;
    check_used_below(*state_, *value_, path);
}

Table::Table(TrackedNode entry, std::vector<std::string> labels, TrackedNode data)
    : entry_(std::move(entry)), labels_(std::move(labels)), data_(std::move(data)) {}

size_t Table::rows() const { return data_.valid() ? data_.size() : 0; }

bool Table::has(const std::string& label) const {
    return std::find(labels_.begin(), labels_.end(), label) != labels_.end();
}

TrackedNode Table::cell(size_t row, const std::string& label) const {
    auto column = std::find(labels_.begin(), labels_.end(), label);
    if (column == labels_.end())
        throw Error(STRUCTMD_ERR_INTERNAL, entry_.path() + ": cell of label '" + label + "', which the table lacks");
    return data_.at(row).at(static_cast<size_t>(column - labels_.begin()));
}

TrackedNode Table::row(size_t row) const { return data_.at(row); }

Table read_table(const TrackedNode& entry, const std::vector<std::string>& required,
                 const std::vector<std::string>& optional, TrailingCells trailing) {
    std::vector<std::string> known = required;
    known.insert(known.end(), optional.begin(), optional.end());

    const TrackedNode labelsNode = entry.at("labels");
    std::vector<std::string> labels;
    for (size_t i = 0; i < labelsNode.size(); ++i) {
        const TrackedNode labelNode = labelsNode.at(i);
        const std::string label = labelNode.as<std::string>();
        if (std::find(known.begin(), known.end(), label) == known.end()) {
            auto suggestion = closest(label, known);
            throw input_error(labelNode.path(), "unknown label '" + label + "' " +
                                                    (suggestion ? "(did you mean " + *suggestion + "?)"
                                                                : "(expected one of " + join(known) + ")"));
        }
        auto first = std::find(labels.begin(), labels.end(), label);
        if (first != labels.end()) {
            const auto firstIndex = static_cast<size_t>(first - labels.begin());
            throw input_error(labelNode.path(), "label '" + label + "' repeats (first at " +
                                                    element_path(labelsNode.path(), firstIndex) + ")");
        }
        labels.push_back(label);
    }
    for (const std::string& label : required)
        if (std::find(labels.begin(), labels.end(), label) == labels.end())
            throw input_error(labelsNode.path(), "missing required label '" + label + "'");

    const TrackedNode data = entry.at("data");
    const size_t rowCount = data.size();
    for (size_t r = 0; r < rowCount; ++r) {
        const json& rowValue = data.json()[r];
        if (rowValue.is_array() && (rowValue.size() == labels.size() ||
                                    (trailing == TrailingCells::ignored && rowValue.size() > labels.size())))
            continue;
        const TrackedNode rowNode = data.at(r);
        if (!rowValue.is_array())
            throw_expected(rowNode, "a row (a list of " + std::to_string(labels.size()) + " cells)");
        throw input_error(rowNode.path(), "row has " + std::to_string(rowValue.size()) + " cells, labels has " +
                                              std::to_string(labels.size()));
    }
    return Table(entry, std::move(labels), data);
}

TrailingCellRows rows_with_trailing_cells(const TrackedNode& entry, size_t labels) {
    TrailingCellRows found;
    const TrackedNode data = entry.at("data");
    for (size_t r = 0; r < data.size(); ++r) {
        const json& row = data.json()[r];
        if (!row.is_array() || row.size() <= labels) continue;
        if (found.count++ == 0) {
            found.firstPath = data.at(r).path();
            found.firstCells = row.size();
        }
    }
    return found;
}

}  // namespace structmd::input
