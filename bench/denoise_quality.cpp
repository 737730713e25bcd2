// bench_denoise: what the denoiser buys (issue 21, docs/denoising.md).
//
// For each scene (the default Cornell box from the repository; Sponza, the
// materials room and the DamagedHelmet from ../shared/data), at a small size:
//   - a converged reference (--ref-spp samples, 16384 by default), rendered
//     once and cached outside the repository (--cache, default
//     ~/.cache/strahl/bench_denoise; delete it to render again);
//   - 16 spp rendered with --denoise: its noisy beauty and the denoised one;
//   - 256 spp without denoising;
// and prints relative MSE, sum (x - r)^2 / (r^2 + 0.01) averaged over pixels
// and channels, and SSIM (luminance after clamping to [0, 1] and a 2.2 gamma,
// 11 x 11 Gaussian windows of sigma 1.5, Wang et al. 2004), then the ratio
// the issue judges: relMSE(denoised 16 spp) / relMSE(256 spp), target < 1.
// Every render runs the strahl binary, with --stats for its timings.
// Finally the speed target on the default scene at 1920 x 1080: denoising
// time / 16-spp render time, target < 1, measured in the same run.

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "cli_render.h"
#include "strahl/core/error.h"

namespace fs = std::filesystem;
using namespace strahl;

namespace {

struct BenchScene {
    std::string name;
    fs::path file;
    bool shared;  // needs ../shared/data
};

struct Options {
    int width = 192, height = 144;
    int refSpp = 16384;
    fs::path cache;
    bool speed = true;
    std::vector<std::string> only;  // scene names; empty: all
};

using bench::Channels;
using bench::readChannels;
using bench::rgb;
using bench::RenderTimes;

// Renders `scene` to `out` (float EXR, no AOVs) with the given size, spp and
// seed, through the strahl binary (bench/cli_render.h).
RenderTimes render(const fs::path& scene, const fs::path& out, int width, int height, int spp,
                   uint64_t seed, bool denoise) {
    std::vector<std::string> args{"--set",  "/film/aovs=[]",         "--width",
                                  std::to_string(width),  "--height", std::to_string(height),
                                  "--spp",  std::to_string(spp),     "--seed",
                                  std::to_string(seed)};
    if (denoise) args.push_back("--denoise");
    return bench::renderWithCli(scene, out, args);
}

double relativeMse(const std::vector<float>& image, const std::vector<float>& reference) {
    double sum = 0.0;
    for (size_t i = 0; i < image.size(); ++i) {
        const double d = double(image[i]) - reference[i];
        sum += d * d / (double(reference[i]) * reference[i] + 0.01);
    }
    return sum / double(image.size());
}

// SSIM of the display luminance (clamped, gamma 2.2), Gaussian windows.
double ssim(const std::vector<float>& image, const std::vector<float>& reference, int width,
            int height) {
    const auto luminance = [&](const std::vector<float>& px) {
        std::vector<double> y(size_t(width) * size_t(height));
        for (size_t i = 0; i < y.size(); ++i) {
            const double l = 0.2126 * px[3 * i] + 0.7152 * px[3 * i + 1] + 0.0722 * px[3 * i + 2];
            y[i] = std::pow(std::clamp(l, 0.0, 1.0), 1.0 / 2.2);
        }
        return y;
    };
    const std::vector<double> x = luminance(image), r = luminance(reference);
    constexpr int kRadius = 5;
    constexpr double kSigma = 1.5, c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
    double total = 0.0;
    int windows = 0;
    for (int cy = kRadius; cy + kRadius < height; ++cy)
        for (int cx = kRadius; cx + kRadius < width; ++cx) {
            double w = 0, mx = 0, mr = 0, xx = 0, rr = 0, xr = 0;
            for (int dy = -kRadius; dy <= kRadius; ++dy)
                for (int dx = -kRadius; dx <= kRadius; ++dx) {
                    const double g = std::exp(-(dx * dx + dy * dy) / (2 * kSigma * kSigma));
                    const size_t i = size_t(cy + dy) * size_t(width) + size_t(cx + dx);
                    w += g;
                    mx += g * x[i];
                    mr += g * r[i];
                    xx += g * x[i] * x[i];
                    rr += g * r[i] * r[i];
                    xr += g * x[i] * r[i];
                }
            mx /= w, mr /= w, xx = xx / w - mx * mx, rr = rr / w - mr * mr, xr = xr / w - mx * mr;
            total +=
                ((2 * mx * mr + c1) * (2 * xr + c2)) / ((mx * mx + mr * mr + c1) * (xx + rr + c2));
            ++windows;
        }
    return windows > 0 ? total / windows : 1.0;
}

Options parse(int argc, char** argv) {
    Options o;
    const char* home = std::getenv("HOME");
    o.cache = fs::path(home ? home : "/tmp") / ".cache/strahl/bench_denoise";
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        const auto next = [&]() -> std::string {
            if (i + 1 >= argc) fail(a, " needs a value");
            return argv[++i];
        };
        if (a == "--width")
            o.width = std::stoi(next());
        else if (a == "--height")
            o.height = std::stoi(next());
        else if (a == "--ref-spp")
            o.refSpp = std::stoi(next());
        else if (a == "--cache")
            o.cache = next();
        else if (a == "--scene")
            o.only.push_back(next());
        else if (a == "--no-speed")
            o.speed = false;
        else
            fail(
                "usage: bench_denoise [--width W] [--height H] [--ref-spp N] [--cache DIR] "
                "[--scene NAME]... [--no-speed]");
    }
    return o;
}

}  // namespace

int main(int argc, char** argv) try {
    std::setvbuf(stdout, nullptr, _IOLBF, 0);  // each line as soon as it is known
    const Options o = parse(argc, argv);
    const fs::path source = STRAHL_SOURCE_DIR;
    const std::vector<BenchScene> scenes{
        {"default", source / "scenes/default.json", false},
        {"sponza", source / "scenes/showcase/sponza.json", true},
        {"materials", source / "scenes/showcase/materials.json", true},
        {"helmet", source / "scenes/showcase/helmet.json", true}};
    const bool haveShared = fs::exists(source / "../shared/data");
    fs::create_directories(o.cache);
    const fs::path work = fs::temp_directory_path() / ("bench_denoise-" + std::to_string(getpid()));
    fs::create_directories(work);

    std::printf("bench_denoise: %dx%d, reference %d spp (cache %s), relMSE and SSIM against it\n",
                o.width, o.height, o.refSpp, o.cache.c_str());
    std::printf("%-10s %14s %14s %14s %9s %9s %9s %10s\n", "scene", "relMSE 16spp", "relMSE 256spp",
                "relMSE 16+dn", "SSIM 16", "SSIM 256", "SSIM dn", "dn/256");
    bool allPass = true;
    for (const BenchScene& s : scenes) {
        if (!o.only.empty() && std::find(o.only.begin(), o.only.end(), s.name) == o.only.end())
            continue;
        if (s.shared && !haveShared) {
            std::printf("%-10s skipped: ../shared/data is not there\n", s.name.c_str());
            continue;
        }
        const fs::path ref =
            o.cache / (s.name + "-" + std::to_string(o.width) + "x" + std::to_string(o.height) +
                       "-" + std::to_string(o.refSpp) + "spp.exr");
        if (!fs::exists(ref)) render(s.file, ref, o.width, o.height, o.refSpp, 1000, false);
        const fs::path low = work / (s.name + "-16.exr"), high = work / (s.name + "-256.exr");
        render(s.file, low, o.width, o.height, 16, 1, true);
        render(s.file, high, o.width, o.height, 256, 2, false);
        const std::vector<float> reference = rgb(readChannels(ref), "");
        const Channels lowChannels = readChannels(low);
        const std::vector<float> noisy = rgb(lowChannels, "noisy."),
                                 denoised = rgb(lowChannels, ""),
                                 many = rgb(readChannels(high), "");
        const double e16 = relativeMse(noisy, reference), e256 = relativeMse(many, reference),
                     eDn = relativeMse(denoised, reference);
        const double ratio = eDn / e256;
        allPass = allPass && ratio < 1.0;
        std::printf("%-10s %14.5f %14.5f %14.5f %9.4f %9.4f %9.4f %9.2f %s\n", s.name.c_str(), e16,
                    e256, eDn, ssim(noisy, reference, o.width, o.height),
                    ssim(many, reference, o.width, o.height),
                    ssim(denoised, reference, o.width, o.height), ratio,
                    ratio < 1.0 ? "PASS" : "FAIL");
    }
    std::printf("ratio dn/256 = relMSE(16 spp denoised) / relMSE(256 spp)  (target < 1)\n");

    if (o.speed) {
        const RenderTimes t = render(scenes[0].file, work / "hd.exr", 1920, 1080, 16, 1, true);
        const double ratio = t.denoise / t.render;
        allPass = allPass && ratio < 1.0;
        std::printf(
            "default scene 1920x1080: render 16 spp %.2f s, denoise %.2f s\n"
            "ratio denoise/render = %.2f  (target < 1) %s\n",
            t.render, t.denoise, ratio, ratio < 1.0 ? "PASS" : "FAIL");
    }
    fs::remove_all(work);
    return allPass ? 0 : 1;
} catch (const std::exception& e) {
    std::fprintf(stderr, "bench_denoise: error: %s\n", e.what());
    return 2;
}
