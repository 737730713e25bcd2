#include "instance_arrays.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <string>
#include <string_view>

#include "strahl/core/error.h"
#include "strahl/core/rng.h"

namespace strahl::scene_detail {

namespace {

// translate(x, y, z) · rotate_y(yaw degrees) · scale(s)
Mat4 placement(Vec3 position, float yawDegrees, float scale) {
    const float yaw = glm::radians(yawDegrees);
    const float c = std::cos(yaw), s = std::sin(yaw);
    Mat4 m(1.0f);  // glm: m[column][row]
    m[0] = Vec4(c * scale, 0.0f, -s * scale, 0.0f);
    m[1] = Vec4(0.0f, scale, 0.0f, 0.0f);
    m[2] = Vec4(s * scale, 0.0f, c * scale, 0.0f);
    m[3] = Vec4(position, 1.0f);
    return m;
}

}  // namespace

std::vector<Mat4> readPlacementFile(const std::filesystem::path& file, uint64_t maxPlacements) {
    const std::string name = file.string();
    std::ifstream in(file, std::ios::binary);
    if (!in) fail(name, ": cannot open the placement file");
    std::vector<Mat4> placements;
    std::string line;
    for (size_t lineNumber = 1; std::getline(in, line); ++lineNumber) {
        const auto error = [&](const auto&... args) { fail(name, ":", lineNumber, ": ", args...); };
        std::string_view text(line);
        if (const size_t hash = text.find('#'); hash != std::string_view::npos)
            text = text.substr(0, hash);
        float v[12];
        int n = 0;
        const char* p = text.data();
        const char* const end = p + text.size();
        while (true) {
            while (p < end && (*p == ' ' || *p == '\t' || *p == '\r' || *p == ',')) ++p;
            if (p == end) break;
            if (n == 12) error("more than 12 numbers");
            float value = 0.0f;
            const auto [next, ec] = std::from_chars(p, end, value);
            if (ec != std::errc() || next == p)
                error("'", std::string_view(p, size_t(end - p)).substr(0, 20), "' is not a number");
            if (!std::isfinite(value)) error("number ", n + 1, " is not finite");
            v[n++] = value;
            p = next;
        }
        if (n == 0) continue;
        if (placements.size() >= maxPlacements)
            error("more than ", maxPlacements, " placements (the instance limit, 2^24)");
        if (n == 12) {
            Mat4 m(1.0f);
            for (int row = 0; row < 3; ++row)
                for (int column = 0; column < 4; ++column) m[column][row] = v[4 * row + column];
            const float det = glm::determinant(Mat3(m));
            if (!std::isfinite(det) || std::abs(det) < 1e-12f)
                error("the matrix is not invertible (determinant ", det, ")");
            placements.push_back(m);
        } else if (n >= 3 && n <= 5) {
            const float scale = n == 5 ? v[4] : 1.0f;
            if (!(scale > 0.0f)) error("the scale ", scale, " is not positive");
            placements.push_back(placement(Vec3(v[0], v[1], v[2]), n >= 4 ? v[3] : 0.0f, scale));
        } else {
            error(n, " numbers; a placement is x y z [yaw [scale]] or 12 matrix entries");
        }
    }
    if (in.bad()) fail(name, ": read error");
    if (placements.empty()) fail(name, ": no placements in the file");
    return placements;
}

std::vector<Mat4> scatterPlacements(const Scatter& scatter) {
    // Stream 0x5ca7: any fixed stream would do; the seed picks the layout.
    Pcg32 rng(scatter.seed, 0x5ca7);
    std::vector<Mat4> placements;
    placements.reserve(scatter.count);
    const auto lerp = [](float a, float b, float t) { return a + (b - a) * t; };
    for (uint64_t i = 0; i < scatter.count; ++i) {
        // Drawn in a fixed order, one after the other (never as function
        // arguments, whose evaluation order C++ leaves open).
        const float x = lerp(scatter.min.x, scatter.max.x, rng.nextFloat());
        const float z = lerp(scatter.min.y, scatter.max.y, rng.nextFloat());
        const float yaw = lerp(scatter.yawMin, scatter.yawMax, rng.nextFloat());
        const float scale = lerp(scatter.scaleMin, scatter.scaleMax, rng.nextFloat());
        placements.push_back(placement(Vec3(x, scatter.height, z), yaw, scale));
    }
    return placements;
}

}  // namespace strahl::scene_detail
