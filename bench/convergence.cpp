// bench_convergence: time to a clean image (issue 20, part 6).
//
// For each scene, renders of increasing effort are compared with a converged
// reference, for four methods: fixed sampling at 4, 8, ... spp and adaptive
// sampling (docs/adaptive.md) at decreasing thresholds (fixed sampling's
// relRMSE at 4 ... 128 spp and the geometric mean of each two, at most 1,
// with a budget of 1024 spp; where two neighbouring thresholds' errors are
// more than 1.5x apart, the threshold between them too, up to twice), each
// with power light selection and with the light BVH (docs/lights.md). Each
// setting gives a point (the median render time of --repeats renders (3)
// from --stats, and the relative RMSE against the reference), where
//     relRMSE = sqrt(mean over pixels and channels of (x - ref)^2 / (ref^2 + 0.01))
// weighs bright and dark pixels alike (the 0.01 keeps black pixels from
// dividing by zero; the same measure as bench_roulette's relVar).
//
// The figure of merit is the time each method needs to reach a given error:
// the error fixed sampling reaches at each --target-spp (64 and 256: a
// moderate and a clean image), read off each
// method's error-time curve by interpolating between the two renders around
// it on log-log axes (error falls as a power of time). speed-up = time of
// fixed sampling with power selection / the method's time at that error.
// Each such line is followed by the mean samples per pixel each method needs
// for the same error, read off the same way: free of the machine's timing
// noise, it separates where the samples go from what they cost.
// --method NAME (repeatable) measures only those methods besides fixed
// sampling, which always runs (it is the baseline and sets the thresholds).
//
// The reference renders with --reference-spp samples (16384) and another seed
// than the measured renders, once: it is cached outside the repository
// (~/.cache/strahl/bench_convergence, or --cache DIR), keyed by the scene
// file's contents, the size and the spp. Its own relative RMSE is about
// that of the 64-spp render divided by 16, small beside the errors measured.
//
// The scenes: the sphere scene of bench/peer_embree_tutorials.sh (the OBJ it
// caches; an implicit sphere stands in if that script has not run), the
// default Cornell box, Sponza when ../shared/data is present, and a room lit
// by 1600 small lamps (3200 emissive triangles, written by the benchmark).
// --svg FILE draws the curves, one panel per scene
// (docs/images/convergence.svg).
//
// On the sphere scene, Embree's own `pathtracer` tutorial (Debian
// embree-tools) gets a curve too, when bench/peer_embree_tutorials.sh has
// cached the scene and its arguments for the tutorial and `pathtracer` and
// `strace` are installed: the tutorial at 4, 8, ... spp (same size, camera,
// light and path length), its render time read from its system calls as that
// script does. The tutorial writes only 8-bit images (its frame buffer is
// linear RGBA8: floor(255.01 clamp(x))), so this comparison quantises
// strahl's renders and the reference the same way and measures relRMSE on
// the quantised values ("relRMSE8"): equal footing, same truncation. Printed:
// the time each needs to reach strahl's fixed-sampling relRMSE8 at each
// target spp, and the ratio pathtracer time / strahl time (> 1: strahl is
// sooner).

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "cli_render.h"
#include "strahl/core/error.h"

namespace fs = std::filesystem;
using namespace strahl;

namespace {

struct Options {
    int width = 160, height = 120;
    int referenceSpp = 16384;
    std::vector<int> targetSpp{64, 256};  // --target-spp replaces them
    std::vector<int> fixedSpp{4, 8, 16, 32, 64, 128, 256};
    // Adaptive thresholds: fixed sampling's relRMSE at these sample counts
    // (a scene's noise per sample decides which thresholds make sense).
    // A pixel threshold t gives an image relRMSE of about t / 3.
    std::vector<int> thresholdSpp{4, 8, 16, 32, 64, 128};
    int adaptiveBudget = 1024;  // the most samples an adaptive pixel takes
    // Renders per point: its time is their median (the image is the same
    // every time: renders are deterministic). Short renders on a shared
    // machine vary by 10 %.
    int repeats = 3;
    fs::path cache;
    fs::path svg;
    std::vector<std::string> only;  // scene names; empty: all
    std::vector<std::string> methods;  // --method: besides fixed, which always runs; empty: all
};

struct BenchScene {
    std::string name;
    fs::path file;
};

struct Point {
    std::string setting;  // "16 spp" or "t 0.02"
    double seconds = 0.0;
    double error = 0.0;  // relRMSE
    double error8 = 0.0;  // relRMSE8: image and reference quantised as the tutorial's output
    double samples = 0.0;  // mean samples per pixel
};

struct Curve {
    std::string scene, method;
    std::vector<Point> points;  // in order of effort
};

struct Method {
    std::string name;
    bool adaptive;
    std::string selection;  // render.light_selection
};
const Method kMethods[] = {{"fixed", false, "power"},
                           {"adaptive", true, "power"},
                           {"bvh", false, "bvh"},
                           {"adaptive+bvh", true, "bvh"}};

// A 20 x 20 m room, 3 m high (no ceiling), under 40 x 40 small lamps (0.1 m
// squares) just below the top: every point is lit mostly by the few lamps
// above it.
void writeLampRoom(const fs::path& file) {
    std::ofstream out(file);
    out << R"({
  "camera": { "eye": [-8.5, 1.6, -8.5], "look_at": [0, 0.8, 0], "up": [0, 1, 0], "fov": 70 },
  "film": { "width": 160, "height": 120 },
  "render": { "integrator": "path", "spp": 16, "max_depth": 4 },
  "materials": [ { "name": "wall", "color": 0.6 }, { "name": "floor", "color": [0.5, 0.45, 0.4] },
                 { "name": "lamp", "type": "emissive", "emission": 30 } ],
  "shapes": [
    { "type": "mesh", "material": "floor",
      "positions": [[-10,0,-10],[10,0,-10],[10,0,10],[-10,0,10]], "indices": [0,2,1,0,3,2] },
    { "type": "mesh", "material": "wall",
      "positions": [[-10,0,-10],[10,0,-10],[10,3,-10],[-10,3,-10], [-10,0,10],[10,0,10],[10,3,10],[-10,3,10]],
      "indices": [0,1,2,0,2,3, 4,6,5,4,7,6, 0,3,7,0,7,4, 1,5,6,1,6,2] },
    { "type": "mesh", "material": "lamp", "positions": [)";
    const int n = 40;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const float x = -9.75f + 0.5f * float(i), z = -9.75f + 0.5f * float(j), h = 0.05f;
            out << (i + j > 0 ? "," : "") << "[" << x - h << ",2.9," << z - h << "],[" << x + h
                << ",2.9," << z - h << "],[" << x + h << ",2.9," << z + h << "],[" << x - h
                << ",2.9," << z + h << "]";
        }
    out << R"(], "indices": [)";
    for (int k = 0; k < n * n; ++k) {
        const int b = 4 * k;  // wound to face down
        out << (k > 0 ? "," : "") << b << "," << b + 1 << "," << b + 2 << "," << b << ","
            << b + 2 << "," << b + 3;
    }
    out << R"(] } ]
}
)";
    if (!out) fail(file.string(), ": cannot write");
}

std::string fileHash(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) fail(file.string(), ": cannot read");
    std::ostringstream bytes;
    bytes << in.rdbuf();
    uint64_t h = 1469598103934665603ull;  // FNV-1a, 64 bit
    for (unsigned char c : bytes.str()) h = (h ^ c) * 1099511628211ull;
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
    return text;
}

double mean(const std::vector<float>& v) {
    double s = 0.0;
    for (float x : v) s += x;
    return v.empty() ? 0.0 : s / double(v.size());
}

double relativeRmse(const std::vector<float>& image, const std::vector<float>& reference) {
    if (image.size() != reference.size()) fail("image and reference differ in size");
    double sum = 0.0;
    for (size_t i = 0; i < image.size(); ++i) {
        const double d = double(image[i]) - reference[i];
        sum += d * d / (double(reference[i]) * reference[i] + 0.01);
    }
    return std::sqrt(sum / double(image.size()));
}

// The effort (render time, or mean samples per pixel) `curve` needs to reach
// `error`, interpolated on log-log axes between the renders around it. If its
// cheapest render is already below `error`, that render's effort: an upper
// bound (*bound is set). -1: never.
double effortToError(const std::vector<Point>& p, double error, double Point::*effort,
                     bool* bound = nullptr) {
    if (bound) *bound = !p.empty() && p.front().error <= error;
    for (size_t i = 1; i < p.size(); ++i) {
        if (p[i].error > error) continue;
        if (p[i - 1].error <= error) return p[i - 1].*effort;  // already there before
        const double f = std::log(p[i - 1].error / error) / std::log(p[i - 1].error / p[i].error);
        return std::exp(std::log(p[i - 1].*effort) +
                        f * (std::log(p[i].*effort) - std::log(p[i - 1].*effort)));
    }
    return p.empty() || p.front().error > error ? -1.0 : p.front().*effort;
}
double timeToError(const std::vector<Point>& p, double error, bool* bound = nullptr) {
    return effortToError(p, error, &Point::seconds, bound);
}
double timeToError(const Curve& curve, double error, bool* bound = nullptr) {
    return timeToError(curve.points, error, bound);
}
// The same on the curve's relRMSE8.
double timeToError8(const Curve& curve, double error, bool* bound = nullptr) {
    std::vector<Point> p = curve.points;
    for (Point& q : p) q.error = q.error8;
    return timeToError(p, error, bound);
}

// The 8-bit value Embree's tutorials write for a linear value (their frame
// buffer: unsigned(255.01 clamp(x, 0, 1)) per channel), as a fraction of 255.
std::vector<float> quantise8(std::vector<float> image) {
    for (float& x : image) x = std::floor(255.01f * std::clamp(x, 0.0f, 1.0f)) / 255.0f;
    return image;
}

// Runs `command` through the shell; throws with `what` if it fails.
void run(const std::string& command, const std::string& what) {
    if (std::system(command.c_str()) != 0) fail(what, " failed: ", command);
}

bool onPath(const std::string& program) {
    return std::system(("command -v " + program + " >/dev/null 2>&1").c_str()) == 0;
}

// One render of Embree's `pathtracer` tutorial: its arguments (camera, light,
// path length, from the cache), `spp`, the size; writes `out` (PFM) and
// returns its render time. The tutorial prints no render time: it is read
// from its system calls (strace, filtered in the kernel so the rendering
// threads are not slowed), from the line "  accels[0]" that --verbose 2
// prints once the BVH is built to the opening of the output image right
// after the frame (bench/peer_embree_tutorials.sh does the same).
double runPathtracer(const std::vector<std::string>& args, int spp, const Options& o,
                     const fs::path& out, const fs::path& work) {
    const fs::path trace = work / "pathtracer.trace", log = work / "pathtracer.log";
    // Appended piece by piece (GCC 12 warns, wrongly, on literal + string).
    std::string command = "strace -f --seccomp-bpf -ttt -e trace=openat,write -o ";
    command += bench::quoted(trace.string());
    command += " stdbuf -oL pathtracer";
    for (const std::string& a : args) {
        command += ' ';
        command += bench::quoted(a);
    }
    command += " --spp ";
    command += std::to_string(spp);
    command += " --size ";
    command += std::to_string(o.width);
    command += ' ';
    command += std::to_string(o.height);
    command += " --verbose 2 -o ";
    command += bench::quoted(out.string());
    command += " >";
    command += bench::quoted(log.string());
    command += " 2>&1";
    run(command, "pathtracer");
    std::ifstream in(trace);
    std::string line, quotedOut = "\"";
    quotedOut += out.string();
    quotedOut += '"';
    double built = 0.0, written = 0.0;
    while (std::getline(in, line)) {
        std::istringstream fields(line);
        std::string pid;
        double when = 0.0;
        if (!(fields >> pid >> when)) continue;
        if (built == 0.0 && line.find("write(1, \"  accels[0]") != std::string::npos) built = when;
        if (line.find("openat(") != std::string::npos &&
            line.find(quotedOut) != std::string::npos)
            written = when;
    }
    if (built == 0.0 || written <= built) fail("pathtracer: no render interval in ", trace.string());
    return written - built;
}

// Log-log plots of the curves, one panel per scene, one colour per method.
void writeSvg(const fs::path& file, const std::vector<Curve>& curves, const Options& o) {
    std::vector<std::string> scenes;
    for (const Curve& c : curves)
        if (std::find(scenes.begin(), scenes.end(), c.scene) == scenes.end()) scenes.push_back(c.scene);
    const double panel = 300, gap = 40, top = 40, height = 260, left0 = 60;
    const double width = left0 + double(scenes.size()) * (panel + gap) + 20;
    std::ofstream out(file);
    out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\""
        << top + height + 90 << "\" font-family=\"sans-serif\" font-size=\"11\">\n"
        << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
    const char* colours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e"};
    for (size_t si = 0; si < scenes.size(); ++si) {
        double tMin = 1e30, tMax = 0.0, eMin = 1e30, eMax = 0.0;
        for (const Curve& c : curves)
            if (c.scene == scenes[si])
                for (const Point& p : c.points) {
                    tMin = std::min(tMin, p.seconds);
                    tMax = std::max(tMax, p.seconds);
                    eMin = std::min(eMin, p.error);
                    eMax = std::max(eMax, p.error);
                }
        // Whole decades around the data.
        const double lt0 = std::floor(std::log10(tMin)), lt1 = std::max(lt0 + 1, std::ceil(std::log10(tMax)));
        const double le0 = std::floor(std::log10(eMin)), le1 = std::max(le0 + 1, std::ceil(std::log10(eMax)));
        const double left = left0 + double(si) * (panel + gap), right = left + panel;
        const double bottom = top + height;
        const auto x = [&](double t) { return left + (std::log10(t) - lt0) / (lt1 - lt0) * panel; };
        const auto y = [&](double e) { return bottom - (std::log10(e) - le0) / (le1 - le0) * height; };
        out << "<text x=\"" << (left + right) / 2 << "\" y=\"" << top - 12
            << "\" text-anchor=\"middle\" font-size=\"13\">" << scenes[si] << "</text>\n";
        for (double d = lt0; d <= lt1; ++d)
            out << "<line x1=\"" << x(std::pow(10, d)) << "\" y1=\"" << top << "\" x2=\""
                << x(std::pow(10, d)) << "\" y2=\"" << bottom << "\" stroke=\"#ddd\"/>\n"
                << "<text x=\"" << x(std::pow(10, d)) << "\" y=\"" << bottom + 14
                << "\" text-anchor=\"middle\">" << std::pow(10, d) << "</text>\n";
        for (double d = le0; d <= le1; ++d)
            out << "<line x1=\"" << left << "\" y1=\"" << y(std::pow(10, d)) << "\" x2=\""
                << right << "\" y2=\"" << y(std::pow(10, d)) << "\" stroke=\"#ddd\"/>\n"
                << "<text x=\"" << left - 4 << "\" y=\"" << y(std::pow(10, d)) + 4
                << "\" text-anchor=\"end\">" << std::pow(10, d) << "</text>\n";
        size_t mi = 0;
        for (const Curve& c : curves) {
            if (c.scene != scenes[si]) continue;
            const char* colour = colours[mi++ % std::size(colours)];
            out << "<polyline fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"2\" points=\"";
            for (const Point& p : c.points) out << x(p.seconds) << "," << y(p.error) << " ";
            out << "\"/>\n";
            for (const Point& p : c.points)
                out << "<circle cx=\"" << x(p.seconds) << "\" cy=\"" << y(p.error)
                    << "\" r=\"2.5\" fill=\"" << colour << "\"/>\n";
        }
    }
    // The legend and the axes' meaning, under the panels.
    double lx = left0;
    const double ly = top + height + 40;
    std::vector<std::string> legend;
    for (const Method& m : kMethods) legend.push_back(m.name);
    for (const Curve& c : curves)
        if (std::find(legend.begin(), legend.end(), c.method) == legend.end()) legend.push_back(c.method);
    for (size_t mi = 0; mi < legend.size(); ++mi) {
        out << "<line x1=\"" << lx << "\" y1=\"" << ly << "\" x2=\"" << lx + 24 << "\" y2=\"" << ly
            << "\" stroke=\"" << colours[mi % std::size(colours)] << "\" stroke-width=\"2\"/>\n"
            << "<text x=\"" << lx + 30 << "\" y=\"" << ly + 4 << "\">" << legend[mi] << "</text>\n";
        lx += legend[mi].size() > 14 ? 230 : 140;
    }
    out << "<text x=\"" << left0 << "\" y=\"" << ly + 26 << "\">x: render time (s), y: relative RMSE "
        << "against " << o.referenceSpp << " spp; " << o.width << "x" << o.height
        << ", log-log (bench_convergence)</text>\n</svg>\n";
    if (!out) fail(file.string(), ": cannot write");
}

Options parse(int argc, char** argv) {
    Options o;
    bool targetGiven = false;
    const char* home = std::getenv("HOME");
    const char* xdg = std::getenv("XDG_CACHE_HOME");
    o.cache = fs::path(xdg ? xdg : (std::string(home ? home : "/tmp") + "/.cache")) / "strahl";
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
        else if (a == "--reference-spp")
            o.referenceSpp = std::stoi(next());
        else if (a == "--target-spp") {
            if (!targetGiven) o.targetSpp.clear();
            targetGiven = true;
            o.targetSpp.push_back(std::stoi(next()));
        } else if (a == "--cache")
            o.cache = next();
        else if (a == "--svg")
            o.svg = next();
        else if (a == "--scene")
            o.only.push_back(next());
        else if (a == "--repeats")
            o.repeats = std::stoi(next());
        else if (a == "--method") {
            o.methods.push_back(next());
            if (std::none_of(std::begin(kMethods), std::end(kMethods),
                             [&](const Method& m) { return m.name == o.methods.back(); }))
                fail("bench_convergence: unknown method '", o.methods.back(),
                     "' (fixed, adaptive, bvh, adaptive+bvh)");
        } else
            fail("usage: bench_convergence [--width W] [--height H] [--reference-spp N] "
                 "[--target-spp N]... [--cache DIR] [--svg FILE] [--repeats N] [--scene NAME]... "
                 "[--method NAME]...");
    }
    if (o.width < 1 || o.height < 1 || o.referenceSpp < 1 || o.repeats < 1 ||
        std::any_of(o.targetSpp.begin(), o.targetSpp.end(), [](int n) { return n < 1; }))
        fail("bench_convergence: sizes and sample counts must be >= 1");
    return o;
}

}  // namespace

int main(int argc, char** argv) try {
    std::setvbuf(stdout, nullptr, _IOLBF, 0);
    const Options o = parse(argc, argv);
    const fs::path source = STRAHL_SOURCE_DIR;
    const fs::path work =
        fs::temp_directory_path() / ("bench_convergence-" + std::to_string(getpid()));
    fs::create_directories(work);
    const fs::path references = o.cache / "bench_convergence";
    fs::create_directories(references);

    std::vector<BenchScene> scenes;
    const fs::path peerSphere = o.cache / "peer_embree/sphere_scene.json";
    // The tutorial's arguments for the same scene, one per line (written by
    // bench/peer_embree_tutorials.sh next to the scene).
    std::vector<std::string> pathtracerArgs;
    if (fs::exists(peerSphere)) {
        scenes.push_back({"sphere", peerSphere});
        std::ifstream in(o.cache / "peer_embree/sphere_scene.pathtracer-args");
        for (std::string line; std::getline(in, line);)
            if (!line.empty()) pathtracerArgs.push_back(line);
        if (pathtracerArgs.empty())
            std::printf("sphere: no curve for Embree's pathtracer: its arguments are not cached "
                        "(run bench/peer_embree_tutorials.sh once)\n");
        else if (!onPath("pathtracer") || !onPath("strace")) {
            std::printf("sphere: no curve for Embree's pathtracer: `pathtracer` or `strace` is not "
                        "installed (scripts/setup.sh installs both)\n");
            pathtracerArgs.clear();
        }
    } else {
        std::printf("sphere: the 2M-triangle OBJ of bench/peer_embree_tutorials.sh is not cached "
                    "(run that script once); an implicit sphere stands in\n");
        bench::writeOpenSphereScene(work / "sphere.json");
        scenes.push_back({"sphere", work / "sphere.json"});
    }
    scenes.push_back({"default", source / "scenes/default.json"});
    if (fs::exists(source / "../shared/data"))
        scenes.push_back({"sponza", source / "scenes/showcase/sponza.json"});
    else
        std::printf("sponza: skipped: ../shared/data is not there\n");
    writeLampRoom(work / "lamps.json");
    scenes.push_back({"lamps", work / "lamps.json"});
    if (!o.only.empty())
        scenes.erase(std::remove_if(scenes.begin(), scenes.end(),
                                    [&](const BenchScene& s) {
                                        return std::find(o.only.begin(), o.only.end(), s.name) ==
                                               o.only.end();
                                    }),
                     scenes.end());

    const std::vector<std::string> size{"--width", std::to_string(o.width), "--height",
                                        std::to_string(o.height)};
    std::string targets;
    for (int n : o.targetSpp) targets += (targets.empty() ? "" : ", ") + std::to_string(n);
    std::printf("bench_convergence: %dx%d, relative RMSE against %d spp references (cached in "
                "%s); target errors: fixed sampling's at %s spp\n",
                o.width, o.height, o.referenceSpp, references.c_str(), targets.c_str());
    std::printf("%-8s %-12s %-8s %10s %9s %8s\n", "scene", "method", "setting", "mean spp",
                "render s", "relRMSE");
    std::vector<Curve> curves;
    for (const BenchScene& s : scenes) {
        const fs::path reference =
            references / (s.name + "-" + fileHash(s.file) + "-" + std::to_string(o.width) + "x" +
                          std::to_string(o.height) + "-" + std::to_string(o.referenceSpp) + ".exr");
        if (!fs::exists(reference)) {
            std::printf("%s: rendering the %d-spp reference (once)...\n", s.name.c_str(),
                        o.referenceSpp);
            std::vector<std::string> args = size;
            // Another seed than the measured renders (seed 1), so its noise is independent.
            args.insert(args.end(), {"--spp", std::to_string(o.referenceSpp), "--seed", "977"});
            const fs::path partial = work / "reference.exr";
            bench::renderWithCli(s.file, partial, args);
            fs::copy_file(partial, reference, fs::copy_options::overwrite_existing);
        }
        const std::vector<float> ref = bench::rgb(bench::readChannels(reference), "");
        const std::vector<float> ref8 = quantise8(ref);

        const auto measure = [&](const std::string& setting, std::vector<std::string> args) {
            args.insert(args.begin(), size.begin(), size.end());
            args.insert(args.end(), {"--seed", "1"});
            const fs::path out = work / "image.exr";
            Point p;
            p.setting = setting;
            std::vector<double> times;
            for (int r = 0; r < o.repeats; ++r) times.push_back(bench::renderWithCli(s.file, out, args).render);
            std::sort(times.begin(), times.end());
            p.seconds = times[times.size() / 2];
            const bench::Channels c = bench::readChannels(out);
            p.error = relativeRmse(bench::rgb(c, ""), ref);
            p.error8 = relativeRmse(quantise8(bench::rgb(c, "")), ref8);
            const auto count = c.find("samples.X");
            p.samples = count != c.end() ? mean(count->second) : 0.0;  // fixed: set by the caller
            return p;
        };
        std::vector<Curve> sceneCurves;
        for (const Method& m : kMethods) {
            // Fixed sampling always runs: it is the baseline and sets the thresholds.
            if (m.name != "fixed" && !o.methods.empty() &&
                std::find(o.methods.begin(), o.methods.end(), m.name) == o.methods.end())
                continue;
            Curve curve{s.name, m.name, {}};
            const std::string selection = "/render/light_selection=\"" + m.selection + "\"";
            if (!m.adaptive) {
                for (int spp : o.fixedSpp) {
                    Point p = measure(std::to_string(spp) + " spp",
                                      {"--spp", std::to_string(spp), "--set", selection});
                    p.samples = spp;
                    curve.points.push_back(p);
                }
            } else {
                // Fixed sampling's errors, and between each two the
                // geometric mean: two points per doubling of the effort, so
                // the interpolation to the target error spans a short step.
                std::vector<double> errors;
                for (const Point& p : sceneCurves.front().points)
                    if (std::find(o.thresholdSpp.begin(), o.thresholdSpp.end(),
                                  int(p.samples)) != o.thresholdSpp.end()) {
                        if (!errors.empty()) errors.push_back(std::sqrt(errors.back() * p.error));
                        errors.push_back(p.error);
                    }
                std::vector<float> thresholds;
                for (double e : errors)
                    // The CLI takes t <= 1: a larger error gives t = 1, the
                    // cheapest adaptive render (most pixels stop at min_samples).
                    if (const float t = float(std::min(e, 1.0)); thresholds.empty() || t < thresholds.back())
                        thresholds.push_back(t);
                const auto adaptivePoint = [&](float t) {
                    char name[16];
                    std::snprintf(name, sizeof name, "t %.3g", double(t));
                    return measure(name, {"--spp", std::to_string(o.adaptiveBudget),
                                          "--adaptive-threshold", std::to_string(t), "--set",
                                          selection});
                };
                std::vector<float> used;  // each point's threshold, in the points' order
                for (float t : thresholds) {
                    curve.points.push_back(adaptivePoint(t));
                    used.push_back(t);
                }
                // Where two neighbouring thresholds give errors more than 1.5x
                // apart (the step from threshold 1, where every pixel stops at
                // min_samples, to the next is the common case), the threshold
                // between them (geometric mean) is rendered too, at most twice
                // per step: the interpolation to a target error then spans a
                // short step, as it does on fixed sampling's curve.
                for (int round = 0; round < 2; ++round)
                    for (size_t k = 0; k + 1 < curve.points.size(); ++k)
                        if (curve.points[k].error > 1.5 * curve.points[k + 1].error) {
                            const float t = std::sqrt(used[k] * used[k + 1]);
                            curve.points.insert(curve.points.begin() + std::ptrdiff_t(k) + 1,
                                                adaptivePoint(t));
                            used.insert(used.begin() + std::ptrdiff_t(k) + 1, t);
                            ++k;  // past the new point: one insertion per step and round
                        }
            }
            for (const Point& p : curve.points)
                std::printf("%-8s %-12s %-8s %10.1f %9.3f %8.4f\n", s.name.c_str(),
                            m.name.c_str(), p.setting.c_str(), p.samples, p.seconds, p.error);
            sceneCurves.push_back(curve);
        }
        const Curve& fixed = sceneCurves.front();
        for (int targetSpp : o.targetSpp) {
            const auto target = std::find_if(fixed.points.begin(), fixed.points.end(),
                                             [&](const Point& p) { return p.samples == targetSpp; });
            if (target == fixed.points.end()) fail("--target-spp must be one of the fixed sample counts");
            const double tFixed = timeToError(fixed, target->error);
            std::printf("%-8s time to relRMSE %.4f (fixed %d spp): fixed %.3f s", s.name.c_str(),
                        target->error, targetSpp, tFixed);
            for (size_t k = 1; k < sceneCurves.size(); ++k) {
                bool bound = false;
                const double t = timeToError(sceneCurves[k], target->error, &bound);
                if (t > 0.0 && bound)  // its cheapest render is already better: at least this fast
                    std::printf(", %s <= %.3f s (>= %.2fx)", sceneCurves[k].method.c_str(), t,
                                tFixed / t);
                else if (t > 0.0)
                    std::printf(", %s %.3f s (%.2fx)", sceneCurves[k].method.c_str(), t, tFixed / t);
                else
                    std::printf(", %s does not reach it", sceneCurves[k].method.c_str());
            }
            std::printf("\n");
            // The same in mean samples per pixel: free of the machine's timing
            // noise, it shows how much of a speed-up is where the samples go
            // and how much their cost.
            std::printf("%-8s spp to relRMSE %.4f (fixed %d spp):", s.name.c_str(), target->error,
                        targetSpp);
            for (size_t k = 1; k < sceneCurves.size(); ++k) {
                bool bound = false;
                const double n =
                    effortToError(sceneCurves[k].points, target->error, &Point::samples, &bound);
                if (n > 0.0)
                    std::printf("%s %s %s%.1f (%s%.2fx)", k == 1 ? "" : ",",
                                sceneCurves[k].method.c_str(), bound ? "<= " : "", n,
                                bound ? ">= " : "", targetSpp / n);
                else
                    std::printf("%s %s does not reach it", k == 1 ? "" : ",",
                                sceneCurves[k].method.c_str());
            }
            std::printf("\n");
        }
        if (s.name == "sphere" && !pathtracerArgs.empty()) {
            // Embree's tutorial, doubling its spp until it is below the
            // smallest target relRMSE8 (at most 4096 spp).
            double lowest = 1e30;
            for (int targetSpp : o.targetSpp)
                for (const Point& p : fixed.points)
                    if (p.samples == targetSpp) lowest = std::min(lowest, p.error8);
            Curve peer{s.name, "embree pathtracer (8-bit)", {}};
            for (int spp = 4; spp <= 4096; spp *= 2) {
                const fs::path out = work / "pathtracer.pfm";
                std::vector<double> times;
                for (int r = 0; r < o.repeats; ++r)
                    times.push_back(runPathtracer(pathtracerArgs, spp, o, out, work));
                std::sort(times.begin(), times.end());
                Point p;
                p.setting = std::to_string(spp) + " spp";
                p.samples = spp;
                p.seconds = times[times.size() / 2];
                // Its output is already 8-bit; quantise8 keeps each value.
                p.error = p.error8 = relativeRmse(quantise8(bench::rgb(bench::readChannels(out), "")), ref8);
                peer.points.push_back(p);
                std::printf("%-8s %-12s %-8s %10.1f %9.3f %8.4f (relRMSE8)\n", s.name.c_str(),
                            "pathtracer", p.setting.c_str(), p.samples, p.seconds, p.error8);
                if (p.error8 < lowest) break;
            }
            for (int targetSpp : o.targetSpp) {
                const auto target = std::find_if(fixed.points.begin(), fixed.points.end(),
                                                 [&](const Point& p) { return p.samples == targetSpp; });
                const double e = target->error8;
                std::printf("%-8s time to relRMSE8 %.4f (strahl fixed %d spp, 8-bit):", s.name.c_str(), e,
                            targetSpp);
                const double tPeer = timeToError8(peer, e);
                for (const Curve& c : sceneCurves) {
                    bool bound = false;
                    const double t = timeToError8(c, e, &bound);
                    if (t <= 0.0)
                        std::printf(" strahl %s does not reach it,", c.method.c_str());
                    else if (tPeer > 0.0)
                        std::printf(" strahl %s %s%.3f s (pathtracer/strahl %s%.2fx),", c.method.c_str(),
                                    bound ? "<= " : "", t, bound ? ">= " : "", tPeer / t);
                    else
                        std::printf(" strahl %s %s%.3f s,", c.method.c_str(), bound ? "<= " : "", t);
                }
                if (tPeer > 0.0)
                    std::printf(" embree pathtracer %.3f s\n", tPeer);
                else
                    std::printf(" embree pathtracer does not reach it within 4096 spp\n");
            }
            sceneCurves.push_back(peer);
        }
        curves.insert(curves.end(), sceneCurves.begin(), sceneCurves.end());
    }
    if (!o.svg.empty()) {
        writeSvg(o.svg, curves, o);
        std::printf("wrote %s\n", o.svg.c_str());
    }
    std::printf("(Nx) = time of fixed sampling with power selection / the method's time to the "
                "same relRMSE (> 1: faster)\n");
    fs::remove_all(work);
    return 0;
} catch (const std::exception& e) {
    std::fprintf(stderr, "bench_convergence: error: %s\n", e.what());
    return 2;
}
