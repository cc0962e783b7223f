#include "input/document_builder.hpp"

#include <vector>

#include "core/error.hpp"

namespace structmd::input {
namespace {

using nlohmann::json;

// The nesting the parser follows: deeper documents are junk, and building paths and messages for
// them costs time and stack.
constexpr size_t kDeepestNesting = 64;

// "line L, column C" of the character at a byte offset; columns count UTF-8 characters, as editors do.
std::string text_position(const std::string& text, size_t offset) {
    offset = std::min(offset, text.size());
    size_t line = 1, lineStart = 0;
    for (size_t i = 0; i < offset; ++i)
        if (text[i] == '\n') {
            ++line;
            lineStart = i + 1;
        }
    size_t column = 1;
    for (size_t i = lineStart; i < offset; ++i)
        if ((static_cast<unsigned char>(text[i]) & 0xC0) != 0x80) ++column;
    return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

// nlohmann's message without its "[json.exception.x.n] parse error at line L, column C: " prefix,
// since the position is given once, in our own form.
std::string parse_reason(const std::string& what) {
    std::string reason = what;
    const size_t idEnd = reason.find("] ");
    if (reason.rfind("[json.exception.", 0) == 0 && idEnd != std::string::npos) reason.erase(0, idEnd + 2);
    const size_t positionEnd = reason.find(": ");
    if (reason.rfind("parse error", 0) == 0 && positionEnd != std::string::npos) reason.erase(0, positionEnd + 2);
    return reason;
}

// Builds the document like nlohmann's own parser, and also records each object's key order
// (nlohmann::json keeps keys sorted) and rejects a key given twice in one object (nlohmann::json
// would keep the last one silently).
class DocumentBuilder : public nlohmann::json_sax<json> {
public:
    DocumentBuilder(const std::string& text, TrackingState& tracking) : text_(text), tracking_(tracking) {}

    bool null() override { return add(json(nullptr)); }
    bool boolean(bool value) override { return add(json(value)); }
    bool number_integer(number_integer_t value) override { return add(json(value)); }
    bool number_unsigned(number_unsigned_t value) override { return add(json(value)); }
    bool number_float(number_float_t value, const string_t&) override { return add(json(value)); }
    bool string(string_t& value) override { return add(json(std::move(value))); }
    bool binary(binary_t& value) override { return add(json::binary(std::move(value))); }

    bool start_object(std::size_t) override {
        check_depth();
        json& object = place(json::object());
        open_.push_back({&object, open_path(), {}});
        return true;
    }
    bool key(string_t& name) override {
        Open& object = open_.back();
        if (object.value->contains(name))
            throw input_error(member_path(object.path, name), "given twice in the same object");
        tracking_.keyOrder[object.path].push_back(name);
        object.key = std::move(name);
        return true;
    }
    bool end_object() override { return close(); }
    bool start_array(std::size_t) override {
        check_depth();
        open_.push_back({&place(json::array()), {}, {}});
        return true;
    }
    bool end_array() override { return close(); }

    bool parse_error(std::size_t position, const std::string&, const json::exception& error) override {
        // position counts the characters read, the offending one included.
        throw Error(STRUCTMD_ERR_INPUT,
                    text_position(text_, position > 0 ? position - 1 : 0) + ": " + parse_reason(error.what()));
    }

private:
    struct Open {
        json* value;
        std::string path;  // objects only
        std::string key;   // objects only: the key whose value comes next
    };

    // Names the member of the innermost object whose value nests too deep.
    void check_depth() const {
        if (open_.size() < kDeepestNesting) return;
        std::string where;
        for (auto it = open_.rbegin(); it != open_.rend(); ++it)
            if (it->value->is_object()) {
                where = member_path(it->path, it->key);
                break;
            }
        throw input_error(where, "objects and arrays nested deeper than " + std::to_string(kDeepestNesting) + " levels");
    }

    bool add(json&& value) {
        place(std::move(value));
        return true;
    }
    bool close() {
        open_.pop_back();
        return true;
    }

    json& place(json&& value) {
        if (open_.empty()) return tracking_.document = std::move(value);
        Open& parent = open_.back();
        if (parent.value->is_array()) {
            parent.value->push_back(std::move(value));
            return parent.value->back();
        }
        return (*parent.value)[parent.key] = std::move(value);
    }

    // Path of the value placed last: every open container holds it, or its ancestor, last.
    std::string open_path() const {
        std::string path;
        for (const Open& container : open_) {
            if (container.value->is_array())
                path += "[" + std::to_string(container.value->size() - 1) + "]";
            else
                path = member_path(path, container.key);
        }
        return path;
    }

    const std::string& text_;
    TrackingState& tracking_;
    std::vector<Open> open_;
};

}  // namespace

void build_document(const std::string& text, TrackingState& tracking) {
    DocumentBuilder builder(text, tracking);
    json::sax_parse(text, &builder, json::input_format_t::json, /*strict=*/true, /*ignore_comments=*/true);
}

}  // namespace structmd::input
