#include "progress_reporter.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

namespace strahl::app {

namespace {
// Bars redraw at most 10 times a second; plain lines appear at each 10% step
// and at least every 10 s so a slow phase still shows signs of life in logs.
// JSON lines are for programs that poll: at most one a second keeps the
// stream small on a long render and still shows the job is alive.
constexpr auto kBarInterval = std::chrono::milliseconds(100);
constexpr auto kLineInterval = std::chrono::seconds(10);
constexpr auto kJsonInterval = std::chrono::seconds(1);
constexpr int kBarWidth = 40;

// Seconds, to the millisecond: JSON readers need no more, and the lines stay short.
double roundSeconds(double seconds) { return std::round(seconds * 1000.0) / 1000.0; }
}  // namespace

ProgressReporter::ProgressReporter(Style style, bool quiet)
    : style_(style), quiet_(quiet), created_(Clock::now()) {
    start_ = lastPrint_ = created_;
}

ProgressReporter::Style ProgressReporter::defaultStyle(bool quiet) {
    if (quiet) return Style::Quiet;
    return isatty(STDERR_FILENO) ? Style::Bar : Style::Lines;
}

void ProgressReporter::begin(const std::string& phase, uint64_t total) {
    std::lock_guard lock(printMutex_);
    phase_ = phase;
    total_ = std::max<uint64_t>(total, 1);
    done_ = 0;
    fraction_ = -1.0;
    start_ = lastPrint_ = Clock::now();
    lastDecile_ = -1;
}

void ProgressReporter::advance(uint64_t amount) {
    done_.fetch_add(amount, std::memory_order_relaxed);
    maybePrint();
}

void ProgressReporter::fraction(double fraction) {
    fraction_.store(fraction, std::memory_order_relaxed);
    maybePrint();
}

void ProgressReporter::end() {
    if (style_ == Style::Quiet) return;
    std::lock_guard lock(printMutex_);
    // A phase measured in units may end short of them (an interrupted
    // render): its last line says how far it got. Fraction phases end done.
    if (style_ == Style::Json)
        printJson("progress", fraction_.load() >= 0.0 ? 1.0 : currentFraction(), true);
    else
        print(1.0, true);
}

void ProgressReporter::passes(int done, int total) {
    passesDone_ = done;
    passesTotal_ = total;
}

void ProgressReporter::passDone(int done) {
    passesDone_ = done;
    if (style_ != Style::Json) return;
    std::lock_guard lock(printMutex_);
    printJson("pass", currentFraction(), false);
}

void ProgressReporter::started(const Start& start) {
    event("start", {{"scene", start.scene},
                    {"frame", start.frame ? nlohmann::ordered_json(*start.frame)
                                          : nlohmann::ordered_json(nullptr)},
                    {"resolution", {start.width, start.height}},
                    {"region", {start.region.x0, start.region.y0, start.region.x1, start.region.y1}},
                    {"spp", start.spp},
                    {"outputs", start.outputs}});
}

void ProgressReporter::skipped(const std::vector<std::string>& outputs) {
    event("skipped", {{"outputs", outputs}, {"exit_status", 0}});
}

void ProgressReporter::note(const std::string& line) {
    if (!quiet_) std::fprintf(stderr, "%s\n", line.c_str());
}

void ProgressReporter::finished(const RunReport& report) {
    using Json = nlohmann::ordered_json;
    event(report.stopped.empty() ? "done" : "interrupted",
          {{"status", runStatus(report)},
           {"stopped", report.stopped.empty() ? Json(nullptr) : Json(report.stopped)},
           {"partial", !report.stopped.empty()},
           {"passes_done", report.samplesDone},
           {"passes_total", report.spp},
           {"outputs", report.outputs},
           {"stats", report.statsFile.empty() ? Json(nullptr) : Json(report.statsFile)},
           {"exit_status", report.exitStatus}});
}

void ProgressReporter::event(const std::string& name, const nlohmann::ordered_json& fields) {
    if (style_ != Style::Json) return;
    nlohmann::ordered_json line;
    line["event"] = name;
    line["elapsed"] = roundSeconds(std::chrono::duration<double>(Clock::now() - created_).count());
    for (const auto& [key, value] : fields.items()) line[key] = value;
    std::lock_guard lock(printMutex_);
    std::printf("%s\n", line.dump().c_str());
    std::fflush(stdout);
}

double ProgressReporter::currentFraction() const {
    return fraction_.load() >= 0.0
               ? fraction_.load()
               : static_cast<double>(done_.load()) / static_cast<double>(total_);
}

void ProgressReporter::maybePrint() {
    if (style_ == Style::Quiet) return;
    std::unique_lock lock(printMutex_, std::try_to_lock);
    if (!lock.owns_lock()) return;  // another thread is printing: skip, never wait
    const double f = currentFraction();
    const auto now = Clock::now();
    if (style_ == Style::Json) {
        if (now - lastPrint_ >= kJsonInterval) printJson("progress", f, false);
    } else if (style_ == Style::Bar) {
        if (now - lastPrint_ >= kBarInterval) print(f, false);
    } else {
        const int decile = static_cast<int>(std::clamp(f, 0.0, 1.0) * 10.0);
        if (decile > lastDecile_ || now - lastPrint_ >= kLineInterval) {
            lastDecile_ = decile;
            print(f, false);
        }
    }
}

// One "progress" or "pass" line; the caller holds printMutex_.
void ProgressReporter::printJson(const char* event, double fraction, bool final) {
    fraction = std::clamp(fraction, 0.0, 1.0);
    const auto now = Clock::now();
    lastPrint_ = now;
    const double phaseElapsed = std::chrono::duration<double>(now - start_).count();
    nlohmann::ordered_json line;
    line["event"] = event;
    line["elapsed"] = roundSeconds(std::chrono::duration<double>(now - created_).count());
    line["phase"] = phase_;
    line["fraction"] = std::round(fraction * 1e4) / 1e4;
    // A phase counted in tile passes whose work is all done has finished every
    // sample pass, though its last passDone() comes after this line.
    const bool allDone = fraction_.load() < 0.0 && done_.load() >= total_;
    line["passes_done"] = allDone && passesTotal_.load() > 0 ? passesTotal_.load() : passesDone_.load();
    line["passes_total"] = passesTotal_.load();
    // The phase's remaining time at its average speed so far; unknown (null)
    // until some of it is done.
    if (final && fraction >= 1.0)
        line["eta"] = 0.0;
    else if (fraction > 0.0 && !final)
        line["eta"] = roundSeconds(phaseElapsed * (1.0 - fraction) / fraction);
    else
        line["eta"] = nullptr;
    std::printf("%s\n", line.dump().c_str());
    std::fflush(stdout);
}

void ProgressReporter::print(double fraction, bool final) {
    fraction = std::clamp(fraction, 0.0, 1.0);
    const auto now = Clock::now();
    lastPrint_ = now;
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    char eta[32] = "--";
    if (fraction > 0.0 && !final)
        std::snprintf(eta, sizeof eta, "%.1f s", elapsed * (1.0 - fraction) / fraction);
    if (style_ == Style::Bar) {
        const int filled = static_cast<int>(fraction * kBarWidth);
        std::string bar(static_cast<size_t>(filled), '#');
        bar.resize(kBarWidth, '.');
        if (final)
            std::fprintf(stderr, "\r%-8s [%s] 100%% in %.2f s\n", phase_.c_str(), bar.c_str(),
                         elapsed);
        else
            std::fprintf(stderr, "\r%-8s [%s] %3d%% ETA %s   ", phase_.c_str(), bar.c_str(),
                         static_cast<int>(fraction * 100.0), eta);
    } else {
        if (final)
            std::fprintf(stderr, "%s: done in %.2f s\n", phase_.c_str(), elapsed);
        else
            std::fprintf(stderr, "%s: %3d%% (elapsed %.1f s, ETA %s)\n", phase_.c_str(),
                         static_cast<int>(fraction * 100.0), elapsed, eta);
    }
    std::fflush(stderr);
}

}  // namespace strahl::app
