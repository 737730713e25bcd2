#include "strahl/job/run_report.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <system_error>

#include <nlohmann/json.hpp>

#include <unistd.h>

#include "strahl/core/error.h"
#include "strahl/film/image_output.h"

namespace strahl {

namespace fs = std::filesystem;

namespace {

double roundSeconds(double seconds) { return std::round(seconds * 1000.0) / 1000.0; }

}  // namespace

std::string runStatus(const RunReport& r) {
    if (r.stopped.empty()) return "complete";
    return r.stopped == "time limit" ? "time limit" : "interrupted";
}

namespace {

nlohmann::ordered_json statsJson(const RunReport& r) {
    nlohmann::ordered_json j;
    j["strahl_version"] = STRAHL_VERSION;
    j["scene"] = r.scene;
    j["frame"] = r.frame ? nlohmann::ordered_json(*r.frame) : nlohmann::ordered_json(nullptr);
    j["resolution"] = {r.width, r.height};
    j["region"] = {r.region.x0, r.region.y0, r.region.x1, r.region.y1};
    j["spp"] = r.spp;
    j["seed"] = r.seed;
    j["integrator"] = r.integrator;
    j["algorithm"] = r.algorithm;
    j["accel"] = r.accel;
    j["samples"] = {{"begin", r.sampleBegin}, {"end", r.sampleEnd}, {"done", r.samplesDone}};
    j["threads"] = r.threads;
    j["timings"] = {{"load", roundSeconds(r.loadSeconds)},
                    {"bvh", roundSeconds(r.bvhSeconds)},
                    {"render", roundSeconds(r.renderSeconds)},
                    {"first_pixel", roundSeconds(r.firstPixelSeconds)},
                    {"denoise", roundSeconds(r.denoiseSeconds)},
                    {"total", roundSeconds(r.totalSeconds)}};
    const uint64_t rays = r.cameraRays + r.shadowRays + r.bounceRays;
    j["rays"] = {{"total", rays},
                 {"camera", r.cameraRays},
                 {"shadow", r.shadowRays},
                 {"bounce", r.bounceRays},
                 {"per_second", r.renderSeconds > 0.0
                                    ? static_cast<uint64_t>(std::llround(
                                          static_cast<double>(rays) / r.renderSeconds))
                                    : uint64_t{0}}};
    j["peak_resident_bytes"] = r.peakResidentBytes;
    j["outputs"] = r.outputs;
    j["status"] = runStatus(r);
    j["partial"] = !r.stopped.empty();
    j["stopped"] = r.stopped.empty() ? nlohmann::ordered_json(nullptr)
                                     : nlohmann::ordered_json(r.stopped);
    j["exit_status"] = r.exitStatus;
    return j;
}

}  // namespace

void checkStatsPath(const fs::path& file) {
    std::error_code ec;
    if (fs::is_directory(file, ec)) fail(file.string(), ": --stats names a folder, not a file");
    const fs::path folder = file.parent_path().empty() ? fs::path(".") : file.parent_path();
    if (!fs::is_directory(folder, ec))
        fail(file.string(), ": cannot write the statistics: folder '", folder.string(),
             "' does not exist");
    // Permissions alone do not tell (ACLs, read-only mounts, root): try it,
    // under a name no one else uses.
    const fs::path probe =
        folder / (".strahl-stats-probe-" + std::to_string(::getpid()) + ".tmp");
    std::FILE* handle = std::fopen(probe.c_str(), "wx");
    if (handle == nullptr) {
        const int error = errno;
        fail(file.string(), ": cannot write the statistics in folder '", folder.string(),
             "': ", std::strerror(error));
    }
    std::fclose(handle);
    fs::remove(probe, ec);
}

void writeStatsFile(const fs::path& file, const RunReport& report) {
    writeTextFileAtomically(file, statsJson(report).dump(2) + "\n");
}

}  // namespace strahl
