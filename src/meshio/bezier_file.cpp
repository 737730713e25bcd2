// The ".bpt" Bézier patch reader; the format is described in
// include/strahl/meshio/bezier_file.h.

#include "strahl/meshio/bezier_file.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <string>

#include "text_scan.h"

namespace fs = std::filesystem;

namespace strahl {

namespace {

using meshio::LineScanner;

// The smallest a patch can be in the file: "3 3\n" and 16 lines "0 0 0\n".
constexpr size_t kMinPatchBytes = 4 + 16 * 6;

// Hands out the lines that hold more than blanks and comments, one at a time.
class LineCursor {
public:
    LineCursor(const std::string& file, const std::string& text) : file_(file), text_(text) {}

    std::optional<LineScanner> next() {
        const char* const end = text_.data() + text_.size();
        while (pos_ < text_.size()) {
            const char* begin = text_.data() + pos_;
            const char* eol =
                static_cast<const char*>(std::memchr(begin, '\n', size_t(end - begin)));
            if (eol == nullptr) eol = end;
            ++line_;
            pos_ = size_t(eol - text_.data()) + 1;
            LineScanner s{file_, line_, begin, eol};
            if (!s.atEnd()) return s;
        }
        return std::nullopt;
    }

    // Bytes not yet handed out.
    size_t remaining() const { return pos_ < text_.size() ? text_.size() - pos_ : 0; }

    // Fails at the end of the file: the line after the last full one.
    template <typename... Args>
    [[noreturn]] void failAtEnd(const Args&... args) const {
        const size_t newlines = size_t(std::count(text_.begin(), text_.end(), '\n'));
        fail(file_, ':', newlines + 1, ": unexpected end of file: ", args...);
    }

private:
    const std::string& file_;
    const std::string& text_;
    size_t pos_ = 0;
    size_t line_ = 0;
};

// The next token as a non-negative integer, or nothing if it is not one.
std::optional<unsigned long long> integer(LineScanner& s) {
    const std::string_view token = s.token();
    unsigned long long value = 0;
    const auto [next, ec] = meshio::parseNumber(token.data(), token.data() + token.size(), value);
    if (token.empty() || ec != std::errc() || next != token.data() + token.size())
        return std::nullopt;
    return value;
}

double finiteCoordinate(LineScanner& s, const char* what) {
    const char* start = s.p;
    const double value = s.number(what);
    if (!std::isfinite(value))
        s.error("the ", what, " '", meshio::trimBlanks({start, size_t(s.p - start)}),
                "' is not finite");
    return value;
}

}  // namespace

std::vector<BezierPatch> loadBezierFile(const fs::path& file) {
    const std::string text = meshio::readWholeFile(file);
    const std::string name = file.string();
    LineCursor lines(name, text);

    std::optional<LineScanner> header = lines.next();
    if (!header) fail(name, ": empty file: expected the number of patches on the first line");
    const char* countStart = header->p;
    const std::optional<unsigned long long> count = integer(*header);
    if (!count)
        header->error("cannot parse the patch count '",
                      meshio::trimBlanks({countStart, size_t(header->p - countStart)}),
                      "' as a non-negative integer");
    if (!header->atEnd()) header->error("unexpected '", header->token(), "' after the patch count");
    if (*count == 0) header->error("the file declares 0 patches");
    // Never trust the count with an allocation: the rest of the file must be
    // able to hold that many patches (the last line may lack its newline).
    const size_t room = (lines.remaining() + 1) / kMinPatchBytes;
    if (*count > room)
        header->error("the patch count ", *count, " is more than the file can hold (", room,
                      " at most: a patch takes at least ", kMinPatchBytes, " bytes)");

    std::vector<BezierPatch> patches(static_cast<size_t>(*count));
    for (size_t k = 0; k < patches.size(); ++k) {
        std::optional<LineScanner> degrees = lines.next();
        if (!degrees)
            lines.failAtEnd("expected the degree line \"3 3\" of patch ", k, " of ", *count);
        const std::string_view whole =
            meshio::trimBlanks({degrees->p, size_t(degrees->end - degrees->p)});
        const std::optional<unsigned long long> du = integer(*degrees);
        const std::optional<unsigned long long> dv = du ? integer(*degrees) : std::nullopt;
        if (!du || !dv || !degrees->atEnd())
            degrees->error("expected the degree line \"3 3\" of patch ", k, ", got '", whole, "'");
        if (*du != 3 || *dv != 3)
            degrees->error("patch ", k, " has degrees ", *du, " ", *dv,
                           "; only bicubic patches (3 3) are supported");
        for (size_t i = 0; i < 16; ++i) {
            std::optional<LineScanner> s = lines.next();
            if (!s) lines.failAtEnd("patch ", k, " has ", i, " of its 16 control points");
            DVec3& p = patches[k].points[i];
            p.x = finiteCoordinate(*s, "x coordinate");
            p.y = finiteCoordinate(*s, "y coordinate");
            p.z = finiteCoordinate(*s, "z coordinate");
            if (!s->atEnd())
                s->error("unexpected '", s->token(), "' after control point ", i, " of patch ", k,
                         " (expected \"x y z\")");
        }
    }
    if (std::optional<LineScanner> extra = lines.next())
        extra->error("unexpected '", extra->token(),
                     "' after the last patch: the first line declares ", *count,
                     *count == 1 ? " patch" : " patches");
    return patches;
}

}  // namespace strahl
