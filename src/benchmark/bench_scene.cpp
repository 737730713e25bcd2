#include "strahl/benchmark/bench_scene.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "strahl/core/error.h"

namespace strahl {

namespace {

// Bumps: 8 around and 8 from pole to pole, 12% of the radius — enough relief
// for bounce rays to hit the mesh again, little enough to keep it a sphere.
constexpr float kBumpHeight = 0.12f;
constexpr float kBumpFrequency = 8.0f;

float bumpyRadius(float theta, float phi) {
    return 1.0f + kBumpHeight * std::sin(kBumpFrequency * theta) * std::sin(kBumpFrequency * phi);
}

}  // namespace

TriangleMesh generateBenchMesh(size_t triangles) {
    // A latitude-longitude sphere: two polar fans of `segments` triangles and
    // rings - 2 bands of 2 * segments, in all 2 * segments * (rings - 1); the
    // ground square adds 2. Segments ≈ 2 * rings keeps the triangles roughly
    // square: rings (rings - 1) ≈ wanted / 4, then segments is rounded to
    // land as near the wanted count as whole numbers allow.
    const double wanted = double(triangles > 2 ? triangles - 2 : 1);
    const int rings = std::max(3, int(std::lround(0.5 * (1.0 + std::sqrt(1.0 + wanted)))));
    const int segments = std::max(3, int(std::lround(wanted / (2.0 * (rings - 1)))));
    TriangleMesh m;
    m.positions.reserve(size_t(rings - 1) * size_t(segments) + 6);
    m.indices.reserve(3 * (size_t(4) * size_t(rings) * size_t(rings) + 2));
    m.positions.emplace_back(0.0f, 1.0f, 0.0f);  // north pole
    for (int r = 1; r < rings; ++r) {
        const float theta = kPi * float(r) / float(rings);
        for (int s = 0; s < segments; ++s) {
            const float phi = 2.0f * kPi * float(s) / float(segments);
            const float radius = bumpyRadius(theta, phi);
            m.positions.emplace_back(radius * std::sin(theta) * std::cos(phi),
                                     radius * std::cos(theta),
                                     radius * std::sin(theta) * std::sin(phi));
        }
    }
    const auto south = static_cast<uint32_t>(m.positions.size());
    m.positions.emplace_back(0.0f, -1.0f, 0.0f);
    auto ringVertex = [&](int r, int s) {  // r in 1 .. rings-1
        return uint32_t(1 + (r - 1) * segments + (s % segments));
    };
    // Counter-clockwise seen from outside.
    for (int s = 0; s < segments; ++s) {
        m.indices.insert(m.indices.end(), {0u, ringVertex(1, s + 1), ringVertex(1, s)});
        m.indices.insert(m.indices.end(),
                         {south, ringVertex(rings - 1, s), ringVertex(rings - 1, s + 1)});
    }
    for (int r = 1; r + 1 < rings; ++r) {
        for (int s = 0; s < segments; ++s) {
            const uint32_t a = ringVertex(r, s), b = ringVertex(r, s + 1);
            const uint32_t c = ringVertex(r + 1, s), d = ringVertex(r + 1, s + 1);
            m.indices.insert(m.indices.end(), {a, b, c, b, d, c});
        }
    }
    // The ground: a square just below the lowest bump, a little wider than the
    // sphere, so the framing (which fits the whole bounding box) keeps the
    // sphere large in the image.
    const float y = -1.0f - kBumpHeight;
    const auto g = static_cast<uint32_t>(m.positions.size());
    m.positions.insert(m.positions.end(), {{-1.8f, y, -1.8f}, {1.8f, y, -1.8f}, {1.8f, y, 1.8f}, {-1.8f, y, 1.8f}});
    m.indices.insert(m.indices.end(), {g, g + 2, g + 1, g, g + 3, g + 2});
    m.reservePadding();
    return m;
}

std::span<const BenchModel> benchModels() {
    static constexpr std::array<BenchModel, 8> kModels = {{
        {"bunny", "stanford-bunny/bun_zipper.ply"},
        {"dragon", "stanford-dragon/dragon_vrip_res2.ply"},
        {"buddha", "happy-buddha-decimated/buddha.obj"},
        {"armadillo", "stanford-armadillo/Armadillo.ply"},
        {"lucy", "stanford-lucy/Lucy100k.ply"},
        {"sponza", "sponza-dabrovic/sponza.obj"},
        {"sibenik", "sibenik/sibenik.obj"},
        {"conference", "conference/conference.obj"},
    }};
    return kModels;
}

size_t parseBenchSize(const std::string& text) {
    // Digits, optionally "e" and an exponent: 1000, 1e3, 2.5e4.
    errno = 0;
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size() || errno != 0 || !std::isfinite(value) ||
        value != std::floor(value) || text.find_first_not_of("0123456789.eE+") != std::string::npos)
        fail("bench: '", text, "' is not a triangle count (write e.g. 1000 or 1e6)");
    if (value < double(kMinBenchTriangles) || value > double(kMaxBenchTriangles))
        fail("bench: a ladder size of ", text, " triangles is outside [", kMinBenchTriangles, ", ",
             kMaxBenchTriangles, "]");
    return static_cast<size_t>(value);
}

std::vector<BenchSceneSpec> benchScenes(std::span<const size_t> ladder,
                                        std::span<const std::string> models,
                                        const std::filesystem::path& dataDir) {
    std::vector<BenchSceneSpec> scenes;
    for (size_t n : ladder) {
        if (n < kMinBenchTriangles || n > kMaxBenchTriangles)
            fail("bench: a ladder size of ", n, " triangles is outside [", kMinBenchTriangles, ", ",
                 kMaxBenchTriangles, "]");
        const int exponent = int(std::lround(std::log10(double(n))));
        const bool powerOfTen = std::pow(10.0, exponent) == double(n);
        scenes.push_back(BenchSceneSpec{
            powerOfTen ? concat("ladder-1e", exponent) : concat("ladder-", n), n, {}});
    }
    if (models.empty()) return scenes;

    std::error_code ec;
    if (!std::filesystem::is_directory(dataDir, ec))
        fail("bench: the data folder ", dataDir.string(),
             " does not exist (give --data DIR, or --models none)");
    std::vector<std::string> names;
    for (const std::string& name : models) {
        if (name == "all") {
            for (const BenchModel& m : benchModels()) names.emplace_back(m.name);
        } else {
            names.push_back(name);
        }
    }
    for (const std::string& name : names) {
        const auto found = std::find_if(benchModels().begin(), benchModels().end(),
                                        [&](const BenchModel& m) { return name == m.name; });
        if (found == benchModels().end()) {
            std::string known;
            for (const BenchModel& m : benchModels()) {
                if (!known.empty()) known += ", ";
                known += m.name;
            }
            fail("bench: unknown model '", name, "' (known: ", known, ", all)");
        }
        const std::filesystem::path file = dataDir / found->file;
        if (!std::filesystem::is_regular_file(file, ec))
            fail("bench: model '", name, "': no file ", file.string());
        scenes.push_back(BenchSceneSpec{name, 0, file});
    }
    return scenes;
}

}  // namespace strahl
