// Mesh loading throughput (issue "large meshed scenes": "Binary PLY load >= 500
// MB/s"). Writes into a temporary folder
//   torus.ply  binary little-endian PLY, float x y z, uchar/int triangle lists,
//              a 2240 x 2240 torus grid: 5.0 M vertices, 10.0 M triangles;
//   torus.obj  a 1000 x 1000 torus grid with normals (f v//vn), 2.0 M triangles,
//              under two usemtl statements;
// then loads each kRounds times with the page cache warm (the first round after
// writing already finds the file cached) and prints, per file, its size, the
// fastest round's seconds and MB/s (1 MB = 10^6 bytes), and in the same run the
// sequential loader's figure and the ratio between them:
//   PLY  sequential = the generic one-value-at-a-time decoder over a copy of
//        the file read with fread, the loader before memory mapping and
//        parallel decoding (still the fallback for ascii and odd layouts);
//   OBJ  sequential = the same parser on one thread (tbb::global_control).
// Then the real meshes in ../shared/data (Stanford PLY models and the OBJ
// scenes), if present, through loadMeshFile with all threads.
//
// Usage: bench_load [--keep]   (--keep leaves the generated files in place)

#include <tbb/global_control.h>
#include <tbb/info.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "../src/meshio/loader_tuning.h"  // internal: the sequential paths
#include "strahl/core/error.h"
#include "strahl/meshio/mesh_file.h"

namespace fs = std::filesystem;

namespace strahl::bench {
namespace {

constexpr int kRounds = 3;
// 2240^2 quads = 10,035,200 triangles (>= 10^7 asked for the PLY).
constexpr uint32_t kPlyGrid = 2240;
// 1000^2 quads = 2,000,000 triangles (>= 2 * 10^6 asked for the OBJ).
constexpr uint32_t kObjGrid = 1000;

Vec3 torusPoint(uint32_t i, uint32_t j, uint32_t n, Vec3* normal = nullptr) {
    constexpr double kR = 1.0, kr = 0.35;
    const double a = 2.0 * std::numbers::pi * i / n, b = 2.0 * std::numbers::pi * j / n;
    const Vec3 nrm(float(std::cos(a) * std::cos(b)), float(std::sin(a) * std::cos(b)),
                   float(std::sin(b)));
    if (normal) *normal = nrm;
    return Vec3(float((kR + kr * std::cos(b)) * std::cos(a)),
                float((kR + kr * std::cos(b)) * std::sin(a)), float(kr * std::sin(b)));
}

// Vertex (i, j) of the n x n periodic grid.
uint32_t gridIndex(uint32_t i, uint32_t j, uint32_t n) {
    return (i % n) * n + (j % n);
}

void writeFile(const fs::path& file, const std::string& bytes) {
    std::FILE* f = std::fopen(file.c_str(), "wb");
    if (!f || std::fwrite(bytes.data(), 1, bytes.size(), f) != bytes.size())
        fail(file.string(), ": cannot write");
    std::fclose(f);
}

template <typename T>
void put(std::string& out, T value) {
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    out.append(bytes, sizeof(T));
}

void writeTorusPly(const fs::path& file, uint32_t n) {
    const uint64_t vertices = uint64_t(n) * n, faces = 2 * vertices;
    std::string out = "ply\nformat binary_little_endian 1.0\ncomment strahl bench_load torus\n"
                      "element vertex " + std::to_string(vertices) +
                      "\nproperty float x\nproperty float y\nproperty float z\n"
                      "element face " + std::to_string(faces) +
                      "\nproperty list uchar int vertex_indices\nend_header\n";
    out.reserve(out.size() + vertices * 12 + faces * 13);
    for (uint32_t i = 0; i < n; ++i) {
        for (uint32_t j = 0; j < n; ++j) {
            const Vec3 p = torusPoint(i, j, n);
            put(out, p.x), put(out, p.y), put(out, p.z);
        }
    }
    for (uint32_t i = 0; i < n; ++i) {
        for (uint32_t j = 0; j < n; ++j) {
            const uint32_t a = gridIndex(i, j, n), b = gridIndex(i + 1, j, n),
                           c = gridIndex(i + 1, j + 1, n), d = gridIndex(i, j + 1, n);
            put(out, uint8_t(3)), put(out, int32_t(a)), put(out, int32_t(b)), put(out, int32_t(c));
            put(out, uint8_t(3)), put(out, int32_t(a)), put(out, int32_t(c)), put(out, int32_t(d));
        }
    }
    writeFile(file, out);
}

void appendNumber(std::string& out, float v) {
    char text[32];
    out.append(text, std::to_chars(text, text + sizeof text, v, std::chars_format::fixed, 6).ptr);
}

void writeTorusObj(const fs::path& file, uint32_t n) {
    std::string out = "# strahl bench_load torus\n";
    for (uint32_t i = 0; i < n; ++i) {
        for (uint32_t j = 0; j < n; ++j) {
            Vec3 normal;
            const Vec3 p = torusPoint(i, j, n, &normal);
            out += "v ", appendNumber(out, p.x), out += ' ', appendNumber(out, p.y), out += ' ',
                appendNumber(out, p.z), out += '\n';
            out += "vn ", appendNumber(out, normal.x), out += ' ', appendNumber(out, normal.y),
                out += ' ', appendNumber(out, normal.z), out += '\n';
        }
    }
    const auto corner = [&](uint32_t v) {
        const std::string s = std::to_string(v + 1);
        out += ' ', out += s, out += "//", out += s;
    };
    for (uint32_t i = 0; i < n; ++i) {
        if (i == 0) out += "usemtl outside\n";
        if (i == n / 2) out += "usemtl inside\n";
        for (uint32_t j = 0; j < n; ++j) {
            const uint32_t a = gridIndex(i, j, n), b = gridIndex(i + 1, j, n),
                           c = gridIndex(i + 1, j + 1, n), d = gridIndex(i, j + 1, n);
            out += 'f', corner(a), corner(b), corner(c), out += '\n';
            out += 'f', corner(a), corner(c), corner(d), out += '\n';
        }
    }
    writeFile(file, out);
}

struct Timing {
    double best = 1e30;
    size_t triangles = 0;
};

Timing timeLoads(const std::function<LoadedMesh()>& load) {
    Timing t;
    for (int round = 0; round < kRounds; ++round) {
        const auto start = std::chrono::steady_clock::now();
        const LoadedMesh m = load();
        const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        t.best = std::min(t.best, s);
        t.triangles = m.mesh.triangleCount();
    }
    return t;
}

void printRow(const std::string& label, double megabytes, const Timing& t) {
    std::printf("%-38s %7.1f MB %9zu tris %7.3f s %7.0f MB/s\n", label.c_str(), megabytes,
                t.triangles, t.best, megabytes / t.best);
}

double megabytesOf(const fs::path& file) {
    return double(fs::file_size(file)) / 1e6;
}

}  // namespace
}  // namespace strahl::bench

int main(int argc, char** argv) {
    using namespace strahl;
    using namespace strahl::bench;
    const bool keep = argc > 1 && std::string(argv[1]) == "--keep";
    // The OBJ's usemtl names no library defines: one warning per load, not wanted here.
    setMeshWarningHandler([](const std::string&) {});
    try {
        const fs::path dir = fs::temp_directory_path() / "strahl-bench-load";
        fs::create_directories(dir);
        const fs::path ply = dir / "torus.ply", obj = dir / "torus.obj";
        std::printf("writing %s and %s ...\n", ply.c_str(), obj.c_str());
        writeTorusPly(ply, kPlyGrid);
        writeTorusObj(obj, kObjGrid);
        std::printf("%d rounds each, page cache warm, fastest round; %d hardware threads\n",
                    kRounds, int(tbb::info::default_concurrency()));

        const double plyMB = megabytesOf(ply), objMB = megabytesOf(obj);
        const Timing plyNew = timeLoads([&] { return loadPly(ply); });
        const Timing plyOld = timeLoads([&] { return meshio::loadPlySequential(ply); });
        printRow("torus.ply  parallel (mmap)", plyMB, plyNew);
        printRow("torus.ply  sequential (fread)", plyMB, plyOld);
        std::printf("PLY ratio parallel/sequential = %.2fx;  binary PLY %.0f MB/s (target >= 500) %s\n",
                    plyOld.best / plyNew.best, plyMB / plyNew.best,
                    plyMB / plyNew.best >= 500.0 ? "PASS" : "FAIL");

        const Timing objNew = timeLoads([&] { return loadObj(obj); });
        Timing objOne;
        {
            tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
            objOne = timeLoads([&] { return loadObj(obj); });
        }
        printRow("torus.obj  parallel", objMB, objNew);
        printRow("torus.obj  one thread", objMB, objOne);
        std::printf("OBJ ratio parallel/one thread = %.2fx\n", objOne.best / objNew.best);

        const fs::path shared = STRAHL_SHARED_DATA;
        const char* const kModels[] = {
            "stanford-armadillo/Armadillo.ply", "stanford-lucy/Lucy100k.ply",
            "stanford-dragon/dragon_vrip_res2.ply", "stanford-bunny/bun_zipper.ply",
            "happy-buddha-decimated/buddha.obj", "conference/conference.obj",
            "sponza-dabrovic/sponza.obj"};
        bool anyModel = false;
        for (const char* model : kModels) {
            const fs::path file = shared / model;
            if (!fs::exists(file)) continue;
            anyModel = true;
            printRow(model, megabytesOf(file), timeLoads([&] { return loadMeshFile(file); }));
        }
        if (!anyModel)
            std::printf("no models of %s found: skipping the real meshes\n", shared.c_str());
        if (!keep) fs::remove_all(dir);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_load: %s\n", e.what());
        return 1;
    }
    return 0;
}
