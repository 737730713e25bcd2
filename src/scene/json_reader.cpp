#include "json_reader.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <limits>
#include <system_error>

namespace strahl::scene_detail {
namespace {

using nlohmann::json;


// "LINE:COLUMN" (1-based; columns count bytes) of the 0-based byte `offset`.
std::string lineColumn(const std::string& text, size_t offset) {
    size_t line = 1, column = 1;
    const size_t end = std::min(offset, text.size());
    for (size_t i = 0; i < end; ++i) {
        if (text[i] == '\n') {
            ++line;
            column = 1;
        } else {
            ++column;
        }
    }
    return concat(line, ":", column);
}

// nlohmann's messages read "[json.exception.parse_error.101] parse error at line
// 1, column 6: syntax error while parsing object separator - unexpected number
// literal; last read: '...'; expected ':'". Keep "unexpected number literal;
// expected ':'": the location is reported separately and the echoed input is noise.
std::string shortReason(const std::string& what) {
    std::string reason = what;
    const size_t bracket = reason.find("] ");
    if (bracket != std::string::npos) reason.erase(0, bracket + 2);
    const size_t dash = reason.find(" - ");
    if (reason.find("syntax error") != std::string::npos && dash != std::string::npos)
        reason.erase(0, dash + 3);
    const size_t lastRead = reason.find("; last read: ");
    if (lastRead != std::string::npos) {
        const size_t expected = reason.rfind("; expected ");
        const bool keepExpected = expected != std::string::npos && expected > lastRead;
        reason = reason.substr(0, lastRead) + (keepExpected ? reason.substr(expected) : "");
    }
    return reason;
}

// The DOM parser reports a number too large for a double (1e400) as out_of_range
// without a position; a SAX pass over the same text recovers where it is.
class ErrorLocator : public json::json_sax_t {
public:
    size_t offset = 0;  // 0-based start of the offending token

    bool null() override { return true; }
    bool boolean(bool) override { return true; }
    bool number_integer(number_integer_t) override { return true; }
    bool number_unsigned(number_unsigned_t) override { return true; }
    bool number_float(number_float_t, const string_t&) override { return true; }
    bool string(string_t&) override { return true; }
    bool binary(binary_t&) override { return true; }
    bool start_object(std::size_t) override { return true; }
    bool key(string_t&) override { return true; }
    bool end_object() override { return true; }
    bool start_array(std::size_t) override { return true; }
    bool end_array() override { return true; }
    bool parse_error(std::size_t position, const std::string& lastToken,
                     const json::exception&) override {
        // `position` counts the characters read, up to the token's last one.
        offset = position >= lastToken.size() ? position - lastToken.size() : 0;
        return false;
    }
};

}  // namespace

json parseJsonText(const std::string& text, const std::string& label) {
    try {
        return json::parse(text, nullptr, /*allow_exceptions=*/true, /*ignore_comments=*/true);
    } catch (const json::parse_error& e) {
        // `byte` is the 1-based index of the last character read: the offending one.
        const size_t offset = e.byte > 0 ? e.byte - 1 : 0;
        fail(label, ":", lineColumn(text, offset), ": syntax error: ", shortReason(e.what()));
    } catch (const json::out_of_range& e) {
        ErrorLocator locator;
        json::sax_parse(text, &locator, json::input_format_t::json, /*strict=*/true,
                        /*ignore_comments=*/true);
        fail(label, ":", lineColumn(text, locator.offset),
             ": syntax error: ", shortReason(e.what()));
    }
}

// --- objects -------------------------------------------------------------------

void JsonValue::requireKeys(std::span<const std::string_view> allowed) const {
    if (!value_->is_object()) fail("expected an object, got ", describe());
    for (const auto& item : value_->items()) {
        if (std::find(allowed.begin(), allowed.end(), item.key()) != allowed.end()) continue;
        fail("unknown key '", item.key(), "' (allowed: ", joinList(allowed), ")");
    }
}

bool JsonValue::has(std::string_view key) const {
    return find(key).has_value();
}

JsonValue JsonValue::get(std::string_view key) const {
    std::optional<JsonValue> child = find(key);
    if (!child) fail("missing key '", key, "'");
    return *child;
}

std::optional<JsonValue> JsonValue::find(std::string_view key) const {
    if (!value_->is_object()) fail("expected an object, got ", describe());
    const auto it = value_->find(key);
    if (it == value_->end()) return std::nullopt;
    return JsonValue(*it, childPointer(key), *label_);
}

// Keys come from the fixed lists of the format, which contain neither '/' nor
// '~', so no RFC 6901 escaping is needed.
std::string JsonValue::childPointer(std::string_view key) const {
    return pointer_ + "/" + std::string(key);
}

// --- arrays --------------------------------------------------------------------

void JsonValue::requireArray() const {
    if (!value_->is_array()) fail("expected an array, got ", describe());
}

size_t JsonValue::size() const {
    requireArray();
    return value_->size();
}

JsonValue JsonValue::at(size_t index) const {
    requireArray();
    return JsonValue((*value_)[index], pointer_ + "/" + std::to_string(index), *label_);
}

// --- scalars -------------------------------------------------------------------

bool JsonValue::boolean() const {
    if (!value_->is_boolean()) fail("expected true or false, got ", describe());
    return value_->get<bool>();
}

std::string JsonValue::string() const {
    if (!value_->is_string()) fail("expected a string, got ", describe());
    return value_->get<std::string>();
}

std::string JsonValue::oneOf(std::span<const std::string_view> choices) const {
    std::string s = string();
    if (std::find(choices.begin(), choices.end(), s) != choices.end()) return s;
    fail("must be one of ", joinList(choices), ", got '", s, "'");
}

float JsonValue::number() const {
    if (!value_->is_number()) fail("expected a number, got ", describe());
    const auto f = static_cast<float>(value_->get<double>());
    if (!std::isfinite(f)) fail("must be a finite number within float range, got ", value_->dump());
    return f;
}

float JsonValue::numberIn(float lo, float hi, std::string_view unit) const {
    const float x = number();
    if (!(x >= lo && x <= hi))
        fail("must be in [", lo, ", ", hi, "]", unit.empty() ? "" : " ", unit, ", got ", x);
    return x;
}

// lo and hi are within +-2^53, so they convert to double exactly.
int64_t JsonValue::integer(int64_t lo, int64_t hi) const {
    if (!value_->is_number()) fail("expected an integer, got ", describe());
    bool inRange = false;
    int64_t result = 0;
    if (value_->is_number_unsigned()) {
        const auto u = value_->get<uint64_t>();
        inRange = hi >= 0 && u <= static_cast<uint64_t>(hi) && (lo <= 0 || u >= uint64_t(lo));
        result = inRange ? static_cast<int64_t>(u) : 0;
    } else if (value_->is_number_integer()) {
        result = value_->get<int64_t>();
        inRange = result >= lo && result <= hi;
    } else {
        const double d = value_->get<double>();
        if (std::trunc(d) != d) fail("expected an integer, got ", describe());
        inRange = d >= static_cast<double>(lo) && d <= static_cast<double>(hi);
        result = inRange ? static_cast<int64_t>(d) : 0;
    }
    if (!inRange) fail("must be between ", lo, " and ", hi, ", got ", value_->dump());
    return result;
}

std::optional<uint64_t> JsonValue::integerOrNone() const {
    if (!value_->is_number()) fail("expected an integer, got ", describe());
    if (value_->is_number_unsigned()) return value_->get<uint64_t>();
    if (value_->is_number_integer()) return std::nullopt;  // negative
    const double d = value_->get<double>();
    if (std::trunc(d) != d) fail("expected an integer, got ", describe());
    if (d >= 0.0 && d < 0x1p64) return static_cast<uint64_t>(d);
    return std::nullopt;
}

uint64_t JsonValue::unsignedInteger(uint64_t hi) const {
    const std::optional<uint64_t> value = integerOrNone();
    if (!value || *value > hi) {
        if (hi == std::numeric_limits<uint64_t>::max())
            fail("must be a non-negative integer, got ", value_->dump());
        fail("must be between 0 and ", hi, ", got ", value_->dump());
    }
    return *value;
}

// --- vectors and colours -------------------------------------------------------

template <size_t N>
std::array<float, N> JsonValue::numbers() const {
    if (!value_->is_array() || value_->size() != N) {
        const std::string found =
            value_->is_array() ? concat("an array of ", value_->size()) : describe();
        fail("expected an array of ", N, " numbers, got ", found);
    }
    std::array<float, N> out{};
    for (size_t i = 0; i < N; ++i) {
        // Read directly on the common path (large inline meshes); at(i) builds
        // the element's pointer only to report an error.
        const json& element = (*value_)[i];
        const float f = element.is_number() ? static_cast<float>(element.get<double>())
                                            : std::numeric_limits<float>::quiet_NaN();
        out[i] = std::isfinite(f) ? f : at(i).number();
    }
    return out;
}

Vec2 JsonValue::vec2() const {
    const auto a = numbers<2>();
    return Vec2(a[0], a[1]);
}

Vec3 JsonValue::vec3() const {
    const auto a = numbers<3>();
    return Vec3(a[0], a[1], a[2]);
}

Color JsonValue::color() const {
    if (value_->is_number()) {
        const float grey = number();
        if (grey < 0.0f) fail("must be >= 0, got ", value_->dump());
        return Color(grey);
    }
    if (!value_->is_array()) fail("expected a number or an array of 3 numbers, got ", describe());
    const auto a = numbers<3>();
    for (size_t i = 0; i < 3; ++i) {
        if (a[i] < 0.0f) at(i).fail("must be >= 0, got ", at(i).raw().dump());
    }
    return Color(a[0], a[1], a[2]);
}

std::string JsonValue::describe() const {
    if (value_->is_number()) return concat("number ", value_->dump());
    return value_->type_name();
}

std::string joinList(std::span<const std::string_view> items) {
    std::string list;
    for (std::string_view item : items) list += (list.empty() ? "" : ", ") + std::string(item);
    return list;
}

std::filesystem::path resolvePath(const std::filesystem::path& folder, const JsonValue& value) {
    const std::string text = value.string();
    if (text.empty()) value.fail("expected a path, got an empty string");
    const std::filesystem::path path(text);
    return (path.is_absolute() ? path : folder / path).lexically_normal();
}

std::filesystem::path resolveExistingFile(const std::filesystem::path& folder,
                                          const JsonValue& value, std::string_view noun) {
    const std::filesystem::path path = resolvePath(folder, value);
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        value.fail("no such ", noun, " '", value.string(), "' (looked at ", path.string(), ")");
    return path;
}

bool hasExtension(const std::filesystem::path& path, std::span<const std::string_view> extensions) {
    std::string ext = path.extension().string();
    for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    for (std::string_view allowed : extensions) {
        if (ext == allowed) return true;
    }
    return false;
}

}  // namespace strahl::scene_detail
