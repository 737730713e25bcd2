// bench_roulette: does Russian roulette pay? (issue 20, part 2)
//
// Roulette ends some paths early to save time and divides the survivors by
// their survival probability, which adds variance. It pays when it saves more
// time than it adds variance: the figure of merit is the efficiency
// 1 / (variance x time) (Veach 1997, sec. 2.4), judged against the same
// scene rendered without roulette.
//
// Roulette is unbiased, so no reference image is needed: each render writes
// the `variance` AOV (the variance of each pixel's mean, docs/output.md), and
// the variance of a render is its mean relative variance,
//     relVar = mean over pixels and channels of var / (mean^2 + 0.01),
// so bright and dark pixels weigh alike (the 0.01 keeps black pixels from
// dividing by zero). Time is the render phase from --stats.
//
// For each scene, every roulette setting (off; then a start bounce and a
// throughput threshold: pbrt-v4's rule is "2, 1", from bounce 2 with
// q = min(1, throughput)) renders --repeats times (seeds 1, 2, ...),
// interleaved; the median relVar and the fastest time (the run least disturbed
// by the rest of a shared machine) give
//     efficiency ratio = (relVar_off x time_off) / (relVar x time)
// (> 1: that roulette pays). The default (render.russian_roulette_depth and
// _threshold's defaults) must be >= 1 - tolerance on every scene.
// The scenes: an open scene like that of bench/peer_embree_tutorials.sh (a
// grey sphere on a ground plane, one point light, black sky; written by the
// benchmark), the default Cornell box, and Sponza and the materials room from
// ../shared/data when present.

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli_render.h"
#include "strahl/core/error.h"
#include "strahl/scene/scene_desc.h"

namespace fs = std::filesystem;
using namespace strahl;

namespace {

struct Options {
    int width = 192, height = 144, spp = 64, repeats = 3;
    // Measurement noise allowed below 1 (time on a shared machine, and the
    // variance estimate itself, are good to a few per cent).
    double tolerance = 0.03;
};

struct Setting {
    bool roulette;
    int depth;        // render.russian_roulette_depth
    float threshold;  // render.russian_roulette_threshold
    std::string name() const {
        char text[32];
        std::snprintf(text, sizeof text, "%d, %.2g", depth, double(threshold));
        return roulette ? text : "off";
    }
};

double fastest(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double relativeVariance(const fs::path& exr) {
    const bench::Channels c = bench::readChannels(exr);
    const std::vector<float> mean = bench::rgb(c, ""), variance = bench::rgb(c, "variance.");
    double sum = 0.0;
    for (size_t i = 0; i < mean.size(); ++i)
        sum += double(variance[i]) / (double(mean[i]) * mean[i] + 0.01);
    return sum / double(mean.size());
}

Options parse(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        const auto next = [&]() -> int {
            if (i + 1 >= argc) fail(a, " needs a value");
            return std::stoi(argv[++i]);
        };
        if (a == "--width")
            o.width = next();
        else if (a == "--height")
            o.height = next();
        else if (a == "--spp")
            o.spp = next();
        else if (a == "--repeats")
            o.repeats = next();
        else
            fail("usage: bench_roulette [--width W] [--height H] [--spp N] [--repeats N]");
    }
    if (o.width < 1 || o.height < 1 || o.spp < 2 || o.repeats < 1)
        fail("bench_roulette: sizes and repeats must be >= 1, spp >= 2");
    return o;
}

}  // namespace

int main(int argc, char** argv) try {
    std::setvbuf(stdout, nullptr, _IOLBF, 0);
    const Options o = parse(argc, argv);
    const fs::path source = STRAHL_SOURCE_DIR;
    const fs::path work = fs::temp_directory_path() / ("bench_roulette-" + std::to_string(getpid()));
    fs::create_directories(work);
    bench::writeOpenSphereScene(work / "open.json");
    struct BenchScene {
        std::string name;
        fs::path file;
    };
    std::vector<BenchScene> scenes{{"open", work / "open.json"},
                                   {"default", source / "scenes/default.json"}};
    if (fs::exists(source / "../shared/data")) {
        scenes.push_back({"sponza", source / "scenes/showcase/sponza.json"});
        scenes.push_back({"materials", source / "scenes/showcase/materials.json"});
    } else {
        std::printf("sponza, materials: skipped: ../shared/data is not there\n");
    }
    const RenderDesc defaults;
    const Setting chosen{true, defaults.russianRouletteDepth, defaults.russianRouletteThreshold};
    std::vector<Setting> settings{{false, 0, 0.0f}, {true, 2, 1.0f},  {true, 5, 1.0f},
                                  {true, 1, 0.5f},  {true, 1, 0.25f}, {true, 1, 0.1f},
                                  {true, 2, 0.5f},  {true, 3, 0.5f}};
    const auto same = [&](const Setting& a) {
        return a.roulette && a.depth == chosen.depth && a.threshold == chosen.threshold;
    };
    if (std::none_of(settings.begin(), settings.end(), same)) settings.push_back(chosen);

    std::printf("bench_roulette: %dx%d, %d spp, max_depth 8, %d interleaved repeats; roulette "
                "settings as 'start bounce, threshold'; default %s\n",
                o.width, o.height, o.spp, o.repeats, chosen.name().c_str());
    std::printf("%-10s %-9s %12s %9s %11s\n", "scene", "roulette", "relVar", "render s",
                "efficiency");
    bool pass = true;
    for (const BenchScene& s : scenes) {
        std::vector<std::vector<double>> variance(settings.size()), seconds(settings.size());
        for (int r = 0; r < o.repeats; ++r)
            for (size_t k = 0; k < settings.size(); ++k) {
                const Setting& st = settings[k];
                const fs::path out = work / (s.name + "-" + std::to_string(k) + ".exr");
                std::vector<std::string> args{
                    "--width", std::to_string(o.width), "--height", std::to_string(o.height),
                    "--spp", std::to_string(o.spp), "--seed", std::to_string(r + 1),
                    "--max-depth", "8", "--aov", "variance", "--set",
                    std::string("/render/russian_roulette=") + (st.roulette ? "true" : "false")};
                if (st.roulette)
                    args.insert(args.end(),
                                {"--set", "/render/russian_roulette_depth=" + std::to_string(st.depth),
                                 "--set", "/render/russian_roulette_threshold=" +
                                              std::to_string(st.threshold)});
                seconds[k].push_back(bench::renderWithCli(s.file, out, args).render);
                variance[k].push_back(relativeVariance(out));
            }
        const double offCost = median(variance[0]) * fastest(seconds[0]);
        for (size_t k = 0; k < settings.size(); ++k) {
            const double ratio = offCost / (median(variance[k]) * fastest(seconds[k]));
            const bool isDefault = same(settings[k]);
            if (isDefault) pass = pass && ratio >= 1.0 - o.tolerance;
            std::printf("%-10s %-9s %12.4g %9.3f %11.2f%s\n", s.name.c_str(),
                        settings[k].name().c_str(), median(variance[k]), fastest(seconds[k]), ratio,
                        isDefault ? (ratio >= 1.0 - o.tolerance ? "  default PASS" : "  default FAIL")
                                  : "");
        }
    }
    std::printf("efficiency = (relVar x time without roulette) / (relVar x time); target for the "
                "default >= %.2f on every scene\n",
                1.0 - o.tolerance);
    fs::remove_all(work);
    return pass ? 0 : 1;
} catch (const std::exception& e) {
    std::fprintf(stderr, "bench_roulette: error: %s\n", e.what());
    return 2;
}
