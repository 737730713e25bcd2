#pragma once
// Progress display on stderr for the long phases (BVH build, render).
//   Bar:   a redrawn single-line bar with percentage and ETA, for terminals.
//   Lines: a plain line every 10% (and at least every 10 s), for logs and CI.
//   Quiet: nothing.
// advance()/setFraction() are thread-safe and cheap: printing is rate-limited
// and done by whichever thread gets the print lock, never waited for.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

namespace strahl {

class ProgressReporter {
public:
    enum class Style { Bar, Lines, Quiet };

    explicit ProgressReporter(Style style) : style_(style) {}
    // Bar if stderr is a terminal, Lines otherwise, Quiet if quiet.
    static Style defaultStyle(bool quiet);

    void begin(const std::string& phase, uint64_t total);
    void advance(uint64_t amount);
    void setFraction(double fraction);  // for phases measured as a fraction
    void end();

private:
    void maybePrint();
    void print(double fraction, bool final);

    using Clock = std::chrono::steady_clock;
    Style style_;
    std::string phase_;
    uint64_t total_ = 1;
    std::atomic<uint64_t> done_{0};
    std::atomic<double> fraction_{-1.0};  // >= 0 when set through setFraction
    Clock::time_point start_{}, lastPrint_{};
    int lastDecile_ = -1;
    std::mutex printMutex_;
};

}  // namespace strahl
