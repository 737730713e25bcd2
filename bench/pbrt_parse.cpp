// bench_pbrt_parse: how fast a pbrt-v4 scene with a large inline
// `trianglemesh` loads, against the same mesh as a binary PLY behind a strahl
// JSON scene (issue 23, part 6). It writes both scenes (a wavy grid of n × n
// vertices, 2 (n − 1)² triangles) to a scratch folder, renders each at
// 1 spp, 64 × 64, three times interleaved, and prints the medians of the
// load time (reading the scene file, importing it, reading the mesh,
// building the world), the time to first pixel, the pbrt file's parse speed
// (file size / load time) and the ratios pbrt / JSON + PLY.
//
//   bench_pbrt_parse [--vertices-per-side N]   (default 1000: 2.0 M triangles)

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli_render.h"

namespace fs = std::filesystem;

namespace {

double height(int i, int j, int n) {
    // Waves, so the BVH is not built over a flat plane.
    return 0.05 * std::sin(12.0 * i / n) * std::cos(9.0 * j / n);
}

double coordinate(int i, int n) { return 2.0 * i / (n - 1) - 1.0; }

void writeScenes(const fs::path& dir, int n) {
    const char* camera = "LookAt 0 2.5 2.5  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 40\n"
                         "Film \"rgb\" \"integer xresolution\" 64 \"integer yresolution\" 64\n"
                         "Sampler \"zsobol\" \"integer pixelsamples\" 1\nWorldBegin\n"
                         "LightSource \"infinite\" \"rgb L\" [1 1 1]\n";
    {
        std::ofstream pbrt(dir / "inline.pbrt");
        pbrt << camera << "Shape \"trianglemesh\"\n\"point3 P\" [\n";
        char line[96];
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                std::snprintf(line, sizeof line, "%.6f %.6f %.6f\n", coordinate(i, n), height(i, j, n),
                              coordinate(j, n));
                pbrt << line;
            }
        pbrt << "]\n\"integer indices\" [\n";
        for (int j = 0; j + 1 < n; ++j)
            for (int i = 0; i + 1 < n; ++i) {
                const int a = j * n + i, b = a + 1, c = a + n + 1, d = a + n;
                pbrt << a << ' ' << b << ' ' << c << ' ' << a << ' ' << c << ' ' << d << '\n';
            }
        pbrt << "]\n";
    }
    {
        // The same mesh in binary little-endian PLY, x mirrored as the pbrt
        // importer mirrors pbrt's world (docs/pbrt.md).
        std::ofstream ply(dir / "grid.ply", std::ios::binary);
        ply << "ply\nformat binary_little_endian 1.0\nelement vertex " << n * n
            << "\nproperty float x\nproperty float y\nproperty float z\nelement face " << 2 * (n - 1) * (n - 1)
            << "\nproperty list uchar int vertex_indices\nend_header\n";
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const float p[3] = {static_cast<float>(-coordinate(i, n)), static_cast<float>(height(i, j, n)),
                                    static_cast<float>(coordinate(j, n))};
                ply.write(reinterpret_cast<const char*>(p), sizeof p);
            }
        for (int j = 0; j + 1 < n; ++j)
            for (int i = 0; i + 1 < n; ++i) {
                const int a = j * n + i, b = a + 1, c = a + n + 1, d = a + n;
                // Winding reversed with the mirror, so the front stays up.
                const int triangles[2][3] = {{a, c, b}, {a, d, c}};
                for (const auto& t : triangles) {
                    const unsigned char three = 3;
                    ply.write(reinterpret_cast<const char*>(&three), 1);
                    ply.write(reinterpret_cast<const char*>(t), sizeof t);
                }
            }
    }
    std::ofstream json(dir / "ply.json");
    json << R"({ "camera": { "eye": [0, 2.5, 2.5], "look_at": [0, 0, 0], "fov": 40 },
  "film": { "width": 64, "height": 64 }, "render": { "integrator": "path", "spp": 1 },
  "lights": [ { "type": "sky", "radiance": 1 } ],
  "shapes": [ { "type": "mesh", "file": "grid.ply" } ] })";
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
    int n = 1000;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--vertices-per-side") == 0 && i + 1 < argc) {
            n = std::max(2, std::atoi(argv[++i]));
        } else {
            std::fprintf(stderr, "usage: bench_pbrt_parse [--vertices-per-side N]\n");
            return 2;
        }
    }
    const fs::path dir = fs::temp_directory_path() / "strahl-bench-pbrt-parse";
    fs::create_directories(dir);
    std::printf("writing a grid of %d x %d vertices (%.2f M triangles) to %s\n", n, n,
                2.0 * (n - 1) * (n - 1) / 1e6, dir.string().c_str());
    std::fflush(stdout);
    writeScenes(dir, n);
    const double pbrtMB = static_cast<double>(fs::file_size(dir / "inline.pbrt")) / 1e6;
    const double plyMB = static_cast<double>(fs::file_size(dir / "grid.ply")) / 1e6;
    std::vector<double> pbrtLoad, pbrtFirst, jsonLoad, jsonFirst;
    constexpr int kRepeats = 3;  // interleaved, medians: the machine is shared
    for (int r = 0; r < kRepeats; ++r) {
        const strahl::bench::RenderTimes p =
            strahl::bench::renderWithCli(dir / "inline.pbrt", dir / "pbrt.exr", {});
        const strahl::bench::RenderTimes j = strahl::bench::renderWithCli(dir / "ply.json", dir / "json.exr", {});
        pbrtLoad.push_back(p.load);
        pbrtFirst.push_back(p.firstPixel);
        jsonLoad.push_back(j.load);
        jsonFirst.push_back(j.firstPixel);
    }
    const double pl = median(pbrtLoad), pf = median(pbrtFirst), jl = median(jsonLoad), jf = median(jsonFirst);
    std::printf("%-34s %10s %10s %14s\n", "scene", "load s", "1st pixel", "file MB/s");
    std::printf("%-34s %10.3f %10.3f %14.1f\n", "pbrt, inline trianglemesh", pl, pf, pbrtMB / pl);
    std::printf("%-34s %10.3f %10.3f %14.1f\n", "strahl JSON + binary PLY", jl, jf, plyMB / jl);
    std::printf("pbrt file %.1f MB, PLY %.1f MB; pbrt / (JSON + PLY): load %.2fx, first pixel %.2fx\n", pbrtMB,
                plyMB, pl / jl, pf / jf);
    fs::remove_all(dir);
    return 0;
}
