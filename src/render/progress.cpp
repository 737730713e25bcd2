#include "strahl/render/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace strahl {

namespace {
// Bars redraw at most 10 times a second; plain lines appear at each 10% step
// and at least every 10 s so a slow phase still shows signs of life in logs.
constexpr auto kBarInterval = std::chrono::milliseconds(100);
constexpr auto kLineInterval = std::chrono::seconds(10);
constexpr int kBarWidth = 40;
}  // namespace

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

void ProgressReporter::setFraction(double fraction) {
    fraction_.store(fraction, std::memory_order_relaxed);
    maybePrint();
}

void ProgressReporter::end() {
    if (style_ == Style::Quiet) return;
    std::lock_guard lock(printMutex_);
    print(1.0, true);
}

void ProgressReporter::maybePrint() {
    if (style_ == Style::Quiet) return;
    std::unique_lock lock(printMutex_, std::try_to_lock);
    if (!lock.owns_lock()) return;  // another thread is printing: skip, never wait
    const double f = fraction_.load() >= 0.0
                         ? fraction_.load()
                         : static_cast<double>(done_.load()) / static_cast<double>(total_);
    const auto now = Clock::now();
    if (style_ == Style::Bar) {
        if (now - lastPrint_ >= kBarInterval) print(f, false);
    } else {
        const int decile = static_cast<int>(std::clamp(f, 0.0, 1.0) * 10.0);
        if (decile > lastDecile_ || now - lastPrint_ >= kLineInterval) {
            lastDecile_ = decile;
            print(f, false);
        }
    }
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

}  // namespace strahl
