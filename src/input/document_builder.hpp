#pragma once
// JSON text into a document whose every object keeps its keys in the order the text gives them
// (nlohmann::json keeps them sorted), refusing a key given twice in one object and nesting deeper
// than a bound, with messages that name the JSON path and the text's line and column.
#include <string>

#include "input/tracked_node.hpp"

namespace structmd::input {

// "parent.key", or "key" at the root.
inline std::string member_path(const std::string& parent, const std::string& key) {
    return parent.empty() ? key : parent + "." + key;
}

// Parses `text` into tracking.document and tracking.keyOrder; throws an input error.
void build_document(const std::string& text, TrackingState& tracking);

}  // namespace structmd::input
