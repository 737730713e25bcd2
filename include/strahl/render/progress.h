#pragma once
// What the render loop reports as it goes. The caller decides how to show it:
// the CLI draws a bar, writes log lines or JSON lines (src/app/progress_reporter.h);
// the distributed scheduler counts tiles the same way.

#include <cstdint>
#include <string>

namespace strahl {

class ProgressSink {
public:
    virtual ~ProgressSink() = default;

    // A phase of `total` units of work starts ("render": tiles times passes).
    virtual void begin(const std::string& phase, uint64_t total) = 0;
    // `amount` more units are done. Called from the worker threads: it must be
    // thread-safe and cheap.
    virtual void advance(uint64_t amount) = 0;
    // The phase is over (finished, cancelled or stopped).
    virtual void end() = 0;
};

}  // namespace strahl
