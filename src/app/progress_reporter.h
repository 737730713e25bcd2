#pragma once
// The CLI's display of a render job (the JobObserver `strahl render` gives
// runRenderJob): the progress of the long phases (BVH build, render) and the
// job's events and log lines.
//   Bar:   a redrawn single-line bar with percentage and ETA on stderr, for terminals.
//   Lines: a plain line on stderr every 10% (and at least every 10 s), for logs and CI.
//   Json:  one JSON object per line on stdout, for farm managers and scripts
//          (the format is in docs/cli.md#progress-as-json): the phases' progress
//          (at most one line a second), every finished sample pass, and the
//          run's events (start, skipped, done, interrupted, error).
//   Quiet: nothing.
// The job's log lines ("wrote out.exr") go to stderr unless --quiet.
// advance()/setFraction() are thread-safe and cheap: printing is rate-limited
// and done by whichever thread gets the print lock, never waited for.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "strahl/job/render_job.h"

namespace strahl::app {

class ProgressReporter final : public JobObserver {
public:
    enum class Style { Bar, Lines, Json, Quiet };

    // `quiet`: no log lines (--quiet), whatever the style.
    ProgressReporter(Style style, bool quiet);
    // Bar if stderr is a terminal, Lines otherwise, Quiet if quiet.
    static Style defaultStyle(bool quiet);

    void begin(const std::string& phase, uint64_t total) override;
    void advance(uint64_t amount) override;
    void fraction(double fraction) override;  // for phases measured as a fraction
    void end() override;

    // The render's sample passes: `done` of `total` samples per pixel. JSON
    // lines carry them; passDone() prints a "pass" line for each finished pass.
    void passes(int done, int total) override;
    void passDone(int done) override;

    // The job's events, as JSON lines; note() prints its line on stderr.
    void started(const Start& start) override;
    void skipped(const std::vector<std::string>& outputs) override;
    void note(const std::string& line) override;
    void finished(const RunReport& report) override;

    // Json: prints {"event": name, "elapsed": seconds since construction,
    // ...fields} as one line and flushes; the other styles print nothing.
    void event(const std::string& name, const nlohmann::ordered_json& fields);
    bool isJson() const { return style_ == Style::Json; }

private:
    void maybePrint();
    void print(double fraction, bool final);
    void printJson(const char* event, double fraction, bool final);
    double currentFraction() const;

    using Clock = std::chrono::steady_clock;
    Style style_;
    bool quiet_;
    std::string phase_;
    uint64_t total_ = 1;
    std::atomic<uint64_t> done_{0};
    std::atomic<double> fraction_{-1.0};  // >= 0 when set through setFraction
    std::atomic<int> passesDone_{0}, passesTotal_{0};
    Clock::time_point created_, start_{}, lastPrint_{};
    int lastDecile_ = -1;
    std::mutex printMutex_;
};

}  // namespace strahl::app
