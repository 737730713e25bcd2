#include "strahl/benchmark/bench_report.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

#include "strahl/benchmark/path_bench.h"
#include "strahl/core/error.h"

namespace strahl {

namespace {

namespace fs = std::filesystem;

std::string lowerExtension(const fs::path& file) {
    std::string ext = file.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

// Writes `text` to a temporary file next to `file`, then renames it over
// `file`: a reader never sees half a file, and a failure leaves nothing.
void writeTextAtomically(const fs::path& file, const std::string& text) {
    std::string tempName = ".";
    tempName += file.filename().string();
    tempName += ".tmp-";
    tempName += std::to_string(getpid());
    const fs::path temp = file.parent_path() / tempName;
    {
        std::ofstream out(temp, std::ios::binary);
        if (!out) fail(file.string(), ": cannot write: ", std::strerror(errno));
        out << text;
        out.flush();
        if (!out) {
            std::error_code ec;
            fs::remove(temp, ec);
            fail(file.string(), ": cannot write: ", std::strerror(errno));
        }
    }
    std::error_code ec;
    fs::rename(temp, file, ec);
    if (ec) {
        fs::remove(temp, ec);
        fail(file.string(), ": cannot write: ", ec.message());
    }
}

std::string fixed(double value, int digits) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.*f", digits, value);
    return buffer;
}

// Three significant digits, without exponent for everyday magnitudes.
std::string sig3(double value) {
    char buffer[64];
    if (value != 0 && (std::abs(value) >= 1e6 || std::abs(value) < 1e-3))
        std::snprintf(buffer, sizeof buffer, "%.2e", value);
    else
        std::snprintf(buffer, sizeof buffer, "%.3g", value);
    return buffer;
}

std::vector<const BenchRow*> ladderRows(std::span<const BenchRow> rows) {
    std::vector<const BenchRow*> ladder;
    for (const BenchRow& row : rows)
        if (row.generated) ladder.push_back(&row);
    return ladder;
}

}  // namespace

namespace {

void requireResultsExtension(const fs::path& file) {
    const std::string ext = lowerExtension(file);
    if (ext != ".csv" && ext != ".json")
        fail(file.string(), ": unknown results format '", ext, "' (use .csv or .json)");
}

void requirePlotExtension(const fs::path& file) {
    if (lowerExtension(file) != ".svg")
        fail(file.string(), ": the plot is written as SVG: give a .svg file");
}

void requireFolder(const fs::path& file) {
    const fs::path parent = fs::absolute(file).parent_path();
    std::error_code ec;
    if (!fs::is_directory(parent, ec))
        fail(file.string(), ": the folder ", parent.string(), " does not exist");
}

}  // namespace

void checkBenchResultsFile(const fs::path& file) {
    requireResultsExtension(file);
    requireFolder(file);
}

void checkBenchPlotFile(const fs::path& file) {
    requirePlotExtension(file);
    requireFolder(file);
}

BenchFits fitBench(std::span<const BenchRow> rows) {
    std::vector<double> n, naive, embree;
    for (const BenchRow* row : ladderRows(rows)) {
        n.push_back(double(row->triangles));
        naive.push_back(row->naiveNanosecondsPerRay());
        embree.push_back(row->singleNanosecondsPerRay());
    }
    return BenchFits{fitPowerLaw(n, naive), fitPowerLaw(n, embree), fitLogarithmic(n, embree)};
}

void printBenchTable(std::FILE* out, std::span<const BenchRow> rows, const BenchFits& fits) {
    std::fprintf(out, "%-13s %10s %8s %8s %8s %8s %8s %8s %8s %8s %8s %9s %9s %8s %9s\n", "scene",
                 "triangles", "load s", "build s", "Mtris/s", "MiB", "packet", "single", "shadow",
                 "diffuse", "naive", "naive n", "speedup", "agree", "raster s");
    std::fprintf(out, "%-13s %10s %8s %8s %8s %8s %8s %8s %8s %8s %8s %9s %9s %8s %9s\n", "", "",
                 "", "", "", "mesh+bvh", "Mrays/s", "Mrays/s", "Mrays/s", "Mrays/s", "Mrays/s",
                 "rays", "per ray", "", "");
    for (const BenchRow& r : rows) {
        std::fprintf(out,
                     "%-13s %10zu %8.3f %8.3f %8.2f %8.1f %8.2f %8.2f %8.2f %8.2f %8s %9zu %9s %7.2f%% "
                     "%9s\n",
                     r.scene.c_str(), r.triangles, r.loadSeconds, r.buildSeconds,
                     r.buildSeconds > 0 ? double(r.triangles) / r.buildSeconds / 1e6 : 0.0,
                     r.meshMegabytes + r.bvhMegabytes, r.packetMrays, r.singleMrays, r.shadowMrays,
                     r.diffuseMrays, sig3(r.naiveMrays).c_str(), r.naiveRays,
                     (sig3(r.speedupSingle) + "x").c_str(), 100.0 * r.naiveAgreement,
                     r.rasterSeconds >= 0 ? fixed(r.rasterSeconds, 4).c_str() : "-");
    }
    std::fprintf(out,
                 "speedup: naive ns per ray / Embree single-ray ns per ray (same threads); "
                 "naive traced 'naive n' evenly spaced camera rays of each image\n");
    if (fits.naive.points >= 2) {
        std::fprintf(out,
                     "growth over the ladder (%zu sizes): naive cost ~ n^%.2f (r2 %.3f), "
                     "Embree cost ~ n^%.2f (r2 %.3f); Embree ns/ray = %.1f + %.1f log10(n) (r2 %.3f)\n",
                     fits.naive.points, fits.naive.slope, fits.naive.r2, fits.embree.slope,
                     fits.embree.r2, fits.embreeLog.a, fits.embreeLog.b, fits.embreeLog.r2);
    }
}

void writeBenchResults(const fs::path& file, std::span<const BenchRow> rows, const BenchFits& fits,
                       const BenchOptions& options) {
    writeBenchResults(file, rows, fits, options, {}, PathBenchOptions{});
}

void writeBenchResults(const fs::path& file, std::span<const BenchRow> rows, const BenchFits& fits,
                       const BenchOptions& options, std::span<const PathBenchRow> pathRows,
                       const PathBenchOptions& pathOptions) {
    requireResultsExtension(file);
    if (lowerExtension(file) == ".csv") {
        // One table of ladder and model rows; the path rows have other
        // columns and are written to JSON only (docs/benchmarks.md).
        std::ostringstream csv;
        csv << "scene,generated,triangles,vertices,load_s,input_mb,build_s,build_mtris_per_s,"
               "mesh_mib,bvh_mib,primary_rays,primary_hits,packet_width,packet_mrays,single_mrays,"
               "shadow_mrays,diffuse_mrays,naive_rays,naive_mrays,naive_agreement,"
               "speedup_single,speedup_packet,raster_s\n";
        for (const BenchRow& r : rows) {
            csv << r.scene << ',' << (r.generated ? 1 : 0) << ',' << r.triangles << ','
                << r.vertices << ',' << r.loadSeconds << ',' << r.inputMegabytes << ','
                << r.buildSeconds << ','
                << (r.buildSeconds > 0 ? double(r.triangles) / r.buildSeconds / 1e6 : 0.0) << ','
                << r.meshMegabytes << ',' << r.bvhMegabytes << ',' << r.primaryRays << ','
                << r.primaryHits << ',' << r.packetWidth << ',' << r.packetMrays << ','
                << r.singleMrays << ',' << r.shadowMrays << ',' << r.diffuseMrays << ','
                << r.naiveRays << ',' << r.naiveMrays << ',' << r.naiveAgreement << ','
                << r.speedupSingle << ',' << r.speedupPacket << ',' << r.rasterSeconds << '\n';
        }
        writeTextAtomically(file, csv.str());
        return;
    }
    nlohmann::ordered_json j;
    j["options"] = {{"resolution", options.resolution},
                    {"threads", options.threads},
                    {"repeats", options.repeats},
                    {"naive_budget", options.naiveBudget}};
    j["rows"] = nlohmann::ordered_json::array();
    for (const BenchRow& r : rows) {
        j["rows"].push_back({{"scene", r.scene},
                             {"generated", r.generated},
                             {"triangles", r.triangles},
                             {"vertices", r.vertices},
                             {"load_s", r.loadSeconds},
                             {"input_mb", r.inputMegabytes},
                             {"build_s", r.buildSeconds},
                             {"mesh_mib", r.meshMegabytes},
                             {"bvh_mib", r.bvhMegabytes},
                             {"primary_rays", r.primaryRays},
                             {"primary_hits", r.primaryHits},
                             {"packet_width", r.packetWidth},
                             {"packet_mrays", r.packetMrays},
                             {"single_mrays", r.singleMrays},
                             {"shadow_mrays", r.shadowMrays},
                             {"diffuse_mrays", r.diffuseMrays},
                             {"naive_rays", r.naiveRays},
                             {"naive_mrays", r.naiveMrays},
                             {"naive_agreement", r.naiveAgreement},
                             {"speedup_single", r.speedupSingle},
                             {"speedup_packet", r.speedupPacket},
                             {"raster_s", r.rasterSeconds}});
    }
    j["fits"] = {{"naive_exponent", fits.naive.slope},
                 {"naive_r2", fits.naive.r2},
                 {"embree_exponent", fits.embree.slope},
                 {"embree_r2", fits.embree.r2},
                 {"embree_log_a_ns", fits.embreeLog.a},
                 {"embree_log_b_ns", fits.embreeLog.b},
                 {"embree_log_r2", fits.embreeLog.r2},
                 {"ladder_points", fits.naive.points}};
    if (!pathRows.empty()) {
        j["path_options"] = {{"resolution", pathOptions.resolution},
                             {"spp", pathOptions.spp},
                             {"max_depth", pathOptions.maxDepth},
                             {"threads", pathOptions.threads}};
        j["path"] = nlohmann::ordered_json::array();
        for (const PathBenchRow& r : pathRows) {
            if (r.skipped) {
                j["path"].push_back({{"scene", r.scene},
                                     {"file", r.file.string()},
                                     {"skipped", true},
                                     {"reason", r.skipReason}});
                continue;
            }
            j["path"].push_back({{"scene", r.scene},
                                 {"file", r.file.string()},
                                 {"skipped", false},
                                 {"width", r.width},
                                 {"height", r.height},
                                 {"spp", r.spp},
                                 {"max_depth", r.maxDepth},
                                 {"triangles", r.triangles},
                                 {"load_s", r.loadSeconds},
                                 {"bvh_s", r.bvhSeconds},
                                 {"setup_s", r.setupSeconds},
                                 {"first_tile_s", r.firstTileSeconds},
                                 {"first_pixel_s", r.firstPixelSeconds()},
                                 {"render_s", r.renderSeconds},
                                 {"samples_per_s", r.samplesPerSecond()},
                                 {"mrays_per_s", r.mraysPerSecond()},
                                 {"rays_per_sample", r.raysPerSample()},
                                 {"camera_rays", r.cameraRays},
                                 {"shadow_rays", r.shadowRays},
                                 {"bounce_rays", r.bounceRays},
                                 {"packet_width", r.packetWidth}});
        }
        if (const auto ratio = pathCostRatio(pathRows, "sponza", "cornell"))
            j["path_cost_ratio"] = {{"scene", "sponza"},
                                    {"base", "cornell"},
                                    {"per_sample", ratio->perSample},
                                    {"per_ray", ratio->perRay}};
    }
    writeTextAtomically(file, j.dump(2) + "\n");
}

// ---- the plot -------------------------------------------------------------------

namespace {

// Plot area in SVG user units, inside margins for the axis labels.
constexpr double kWidth = 720, kHeight = 480;
constexpr double kLeft = 80, kRight = 170, kTop = 40, kBottom = 60;

struct Axes {
    double x0, x1, y0, y1;  // decades shown: [10^x0, 10^x1] x [10^y0, 10^y1]
    double px(double value) const {
        return kLeft + (std::log10(value) - x0) / (x1 - x0) * (kWidth - kLeft - kRight);
    }
    double py(double value) const {
        return kHeight - kBottom -
               (std::log10(value) - y0) / (y1 - y0) * (kHeight - kTop - kBottom);
    }
};

}  // namespace

void writeBenchPlot(const fs::path& file, std::span<const BenchRow> rows, const BenchFits& fits) {
    requirePlotExtension(file);
    double nMin = 1e300, nMax = 0, cMin = 1e300, cMax = 0;
    for (const BenchRow& r : rows) {
        for (double c : {r.naiveNanosecondsPerRay(), r.singleNanosecondsPerRay()}) {
            if (c <= 0) continue;
            cMin = std::min(cMin, c);
            cMax = std::max(cMax, c);
        }
        nMin = std::min(nMin, double(r.triangles));
        nMax = std::max(nMax, double(r.triangles));
    }
    if (nMax <= 0 || cMax <= 0) fail(file.string(), ": nothing to plot");
    // Whole decades, with room (a factor 2) so no point sits on the frame.
    const double x0 = std::floor(std::log10(nMin / 2)), y0 = std::floor(std::log10(cMin / 2));
    const Axes axes{x0, std::max(std::ceil(std::log10(nMax * 2)), x0 + 1), y0,
                    std::max(std::ceil(std::log10(cMax * 2)), y0 + 1)};

    std::ostringstream svg;
    svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << kWidth << "\" height=\""
        << kHeight << "\" viewBox=\"0 0 " << kWidth << ' ' << kHeight
        << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
        << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
        << "<text x=\"" << kLeft << "\" y=\"24\" font-size=\"15\">Cost per camera ray: naive "
           "O(n) against Embree's BVH</text>\n";
    // Decade grid and labels.
    for (double e = axes.x0; e <= axes.x1 + 1e-9; e += 1) {
        const double x = axes.px(std::pow(10.0, e));
        svg << "<line x1=\"" << x << "\" y1=\"" << kTop << "\" x2=\"" << x << "\" y2=\""
            << kHeight - kBottom << "\" stroke=\"#ddd\"/>\n"
            << "<text x=\"" << x << "\" y=\"" << kHeight - kBottom + 18
            << "\" text-anchor=\"middle\">1e" << int(e) << "</text>\n";
    }
    for (double e = axes.y0; e <= axes.y1 + 1e-9; e += 1) {
        const double y = axes.py(std::pow(10.0, e));
        svg << "<line x1=\"" << kLeft << "\" y1=\"" << y << "\" x2=\"" << kWidth - kRight
            << "\" y2=\"" << y << "\" stroke=\"#ddd\"/>\n"
            << "<text x=\"" << kLeft - 8 << "\" y=\"" << y + 4 << "\" text-anchor=\"end\">1e"
            << int(e) << "</text>\n";
    }
    svg << "<rect x=\"" << kLeft << "\" y=\"" << kTop << "\" width=\"" << kWidth - kLeft - kRight
        << "\" height=\"" << kHeight - kTop - kBottom << "\" fill=\"none\" stroke=\"black\"/>\n"
        << "<text x=\"" << (kLeft + kWidth - kRight) / 2 << "\" y=\"" << kHeight - 18
        << "\" text-anchor=\"middle\">triangles</text>\n"
        << "<text transform=\"translate(22," << (kTop + kHeight - kBottom) / 2
        << ") rotate(-90)\" text-anchor=\"middle\">ns per ray</text>\n";

    struct Series {
        const char* name;
        const char* colour;
        double (BenchRow::*cost)() const;
        const PowerFit* fit;
    };
    const Series series[] = {{"naive", "#c0392b", &BenchRow::naiveNanosecondsPerRay, &fits.naive},
                             {"Embree", "#2471a3", &BenchRow::singleNanosecondsPerRay, &fits.embree}};
    double legendY = kTop + 10;
    for (const Series& s : series) {
        // Fitted line over the ladder's span.
        if (s.fit->points >= 2) {
            std::vector<double> ladderN;
            for (const BenchRow& r : rows)
                if (r.generated) ladderN.push_back(double(r.triangles));
            const double a = *std::min_element(ladderN.begin(), ladderN.end());
            const double b = *std::max_element(ladderN.begin(), ladderN.end());
            auto fitted = [&](double n) {
                return std::pow(10.0, s.fit->intercept + s.fit->slope * std::log10(n));
            };
            svg << "<line x1=\"" << axes.px(a) << "\" y1=\"" << axes.py(fitted(a)) << "\" x2=\""
                << axes.px(b) << "\" y2=\"" << axes.py(fitted(b)) << "\" stroke=\"" << s.colour
                << "\" stroke-dasharray=\"6 4\"/>\n";
        }
        for (const BenchRow& r : rows) {
            const double c = (r.*s.cost)();
            if (c <= 0) continue;
            const double x = axes.px(double(r.triangles)), y = axes.py(c);
            if (r.generated)
                svg << "<circle cx=\"" << x << "\" cy=\"" << y << "\" r=\"4\" fill=\"" << s.colour
                    << "\"><title>" << r.scene << ": " << sig3(c) << " ns</title></circle>\n";
            else
                svg << "<rect x=\"" << x - 4 << "\" y=\"" << y - 4
                    << "\" width=\"8\" height=\"8\" fill=\"none\" stroke=\"" << s.colour
                    << "\"><title>" << r.scene << ": " << sig3(c) << " ns</title></rect>\n";
        }
        const double lx = kWidth - kRight + 14;
        svg << "<circle cx=\"" << lx << "\" cy=\"" << legendY << "\" r=\"4\" fill=\"" << s.colour
            << "\"/>\n<text x=\"" << lx + 10 << "\" y=\"" << legendY + 4 << "\">" << s.name
            << "</text>\n";
        if (s.fit->points >= 2)
            svg << "<text x=\"" << lx + 10 << "\" y=\"" << legendY + 20 << "\" font-size=\"11\">~ n^"
                << fixed(s.fit->slope, 2) << "</text>\n";
        legendY += 44;
    }
    const double lx = kWidth - kRight + 14;
    svg << "<circle cx=\"" << lx << "\" cy=\"" << legendY << "\" r=\"4\" fill=\"#555\"/>\n"
        << "<text x=\"" << lx + 10 << "\" y=\"" << legendY + 4 << "\">generated ladder</text>\n"
        << "<rect x=\"" << lx - 4 << "\" y=\"" << legendY + 16
        << "\" width=\"8\" height=\"8\" fill=\"none\" stroke=\"#555\"/>\n"
        << "<text x=\"" << lx + 10 << "\" y=\"" << legendY + 24 << "\">real models</text>\n"
        << "<text x=\"" << lx + 10 << "\" y=\"" << legendY + 44
        << "\" font-size=\"11\">dashed: fits</text>\n"
        << "</svg>\n";
    writeTextAtomically(file, svg.str());
}

}  // namespace strahl
