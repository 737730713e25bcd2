#pragma once
// Internal helpers shared by the OBJ, MTL and PLY readers: whole-file reading,
// warnings, and strict whitespace/number scanning with std::from_chars (no
// locale, no allocation), line by line. Not part of the public meshio interface.

#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <string_view>
#include <system_error>

#include "strahl/core/error.h"

namespace strahl::meshio {

// The whole file as bytes; throws "file: cannot open: <strerror>" when it is
// missing or unreadable, and "file: cannot open: not a regular file" for a
// device, FIFO or socket. (Defined in mesh_file.cpp.)
std::string readWholeFile(const std::filesystem::path& file);

// Throws "file: cannot open: not a regular file" for an existing device, FIFO
// or socket (a folder or a missing file is left to the open that follows). A
// device such as /dev/zero never ends and a FIFO blocks the open, so an mtllib
// line or a scene's Bezier patch file naming one would exhaust memory or hang
// (found by fuzz/fuzz_obj and fuzz_scene_json; the inputs are in
// tests/data/fuzz/). Call it before opening. (Defined in mesh_file.cpp.)
void refuseSpecialFile(const std::filesystem::path& file);

// Prints "strahl: warning: <message>" as one line on stderr.
void warn(const std::string& message);

// ASCII lower case; file and material names are compared byte-wise otherwise.
std::string toLower(std::string_view s);

// Blank = whitespace that does not end a line ('\r' counts, so CRLF files work).
inline bool isBlank(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

inline std::string_view trimBlanks(std::string_view s) {
    while (!s.empty() && isBlank(s.front())) s.remove_prefix(1);
    while (!s.empty() && isBlank(s.back())) s.remove_suffix(1);
    return s;
}

// std::from_chars plus the leading '+' it does not accept.
template <typename T>
std::from_chars_result parseNumber(const char* first, const char* last, T& value) {
    if (last - first > 1 && first[0] == '+' && first[1] != '+' && first[1] != '-') ++first;
    return std::from_chars(first, last, value);
}

// Cursor over one line of a text file (OBJ or MTL) whose errors read
// "file:line: what".
struct LineScanner {
    const std::string& file;
    size_t line;
    const char* p;    // next unread character
    const char* end;  // end of the line, excluding '\n'

    template <typename... Args>
    [[noreturn]] void error(const Args&... args) const {
        fail(file, ':', line, ": ", args...);
    }

    // Skips blanks; true when nothing but blanks or a '#' comment remains.
    bool atEnd() {
        while (p < end && isBlank(*p)) ++p;
        return p == end || *p == '#';
    }

    // The next blank-separated token (empty at the end of the line).
    std::string_view token() {
        while (p < end && isBlank(*p)) ++p;
        const char* start = p;
        while (p < end && !isBlank(*p)) ++p;
        return {start, size_t(p - start)};
    }

    // Fails unless only blanks or a comment remain after a `statement`.
    void expectEnd(const char* statement) {
        if (!atEnd())
            error("unexpected '", token(), "' at the end of the ", statement, " statement");
    }

    // Everything left on the line, without surrounding blanks (names may hold spaces).
    std::string_view rest() {
        std::string_view s = trimBlanks({p, size_t(end - p)});
        p = end;
        return s;
    }

    // The next token as a number; `what` names it in the error message.
    double number(const char* what) {
        if (atEnd()) error("missing ", what);
        const char* start = p;
        while (p < end && !isBlank(*p)) ++p;
        const std::string_view text(start, size_t(p - start));
        double value = 0.0;
        const auto [next, ec] = parseNumber(start, p, value);
        if (ec == std::errc::result_out_of_range) error(what, " '", text, "' is out of range");
        if (ec != std::errc() || next != p)
            error("cannot parse ", what, " '", text, "' as a number");
        return value;
    }

    // A number that must be finite and fit a float (coordinates, colours).
    float finiteFloat(const char* what) {
        const char* start = p;
        const double value = number(what);
        const float f = static_cast<float>(value);
        if (!std::isfinite(f))
            error(what, " '", trimBlanks({start, size_t(p - start)}), "' is not a finite float");
        return f;
    }
};

// Calls fn(scanner) for every line of `text`, numbering them from `firstLine`.
template <typename Fn>
void forEachLine(const std::string& file, std::string_view text, Fn&& fn, size_t firstLine = 1) {
    const char* p = text.data();
    const char* const end = p + text.size();
    for (size_t line = firstLine; p < end; ++line) {
        const char* eol = static_cast<const char*>(std::memchr(p, '\n', size_t(end - p)));
        if (eol == nullptr) eol = end;
        LineScanner scanner{file, line, p, eol};
        fn(scanner);
        p = eol + (eol < end ? 1 : 0);
    }
}

}  // namespace strahl::meshio
