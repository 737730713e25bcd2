// The strand-file reader; the format is described in
// include/strahl/meshio/curve_file.h.

#include "strahl/meshio/curve_file.h"

#include <string>

#include "text_scan.h"

namespace strahl {

StrandFile loadStrandFile(const std::filesystem::path& file) {
    meshio::refuseSpecialFile(file);
    const std::string text = meshio::readWholeFile(file);
    const std::string name = file.string();
    StrandFile strands;
    uint32_t current = 0;  // points of the strand being read
    const auto endStrand = [&] {
        if (current > 0) strands.strandPoints.push_back(current);
        current = 0;
    };
    meshio::forEachLine(name, text, [&](meshio::LineScanner& s) {
        const bool blank = s.atEnd();
        if (blank && (s.p == s.end || *s.p != '#')) {
            endStrand();  // an empty line, not a comment line
            return;
        }
        if (blank) return;
        Vec4 p;
        p.x = s.finiteFloat("x coordinate");
        p.y = s.finiteFloat("y coordinate");
        p.z = s.finiteFloat("z coordinate");
        p.w = s.finiteFloat("radius");
        if (p.w < 0.0f) s.error("radius ", p.w, " is negative");
        s.expectEnd("control point (x y z radius)");
        if (strands.points.size() >= UINT32_MAX) s.error("more than 2^32 control points");
        strands.points.push_back(p);
        ++current;
    });
    endStrand();
    if (strands.points.empty()) fail(name, ": no control points (expected lines 'x y z radius')");
    return strands;
}

}  // namespace strahl
