#pragma once
// EmbreeDevice: one RTCDevice with error and memory-monitor callbacks.
//
// Embree reports errors through a callback that must not throw (it runs inside
// Embree, possibly on a worker thread), so the callback only records the first
// message; check() turns it into a strahl::Error on the calling thread after
// each Embree call that can fail. The memory monitor keeps a running total of
// the bytes Embree allocates, which `strahl info` reports, and, given a limit,
// refuses the allocation that would pass it: Embree then stops the call with
// RTC_ERROR_OUT_OF_MEMORY and check() says which limit was reached.

#include <embree3/rtcore.h>

#include <atomic>
#include <mutex>
#include <string>

namespace strahl {

class EmbreeDevice {
public:
    // limitBytes 0: no limit; otherwise Embree may hold at most
    // limitBytes - baselineBytes (the rest of the process holds baselineBytes).
    EmbreeDevice(int threads, size_t limitBytes = 0, size_t baselineBytes = 0);
    ~EmbreeDevice();
    EmbreeDevice(const EmbreeDevice&) = delete;
    EmbreeDevice& operator=(const EmbreeDevice&) = delete;

    RTCDevice handle() const { return device_; }
    // Throws strahl::Error if Embree reported an error since the last check.
    void check(const char* what);
    size_t bytesInUse() const { return static_cast<size_t>(bytes_.load()); }
    bool supportsNative16() const { return native16_; }
    bool supportsNative8() const { return native8_; }

private:
    static void onError(void* self, RTCError code, const char* message);
    static bool onMemory(void* self, ssize_t bytes, bool post);

    RTCDevice device_ = nullptr;
    std::atomic<long long> bytes_{0};
    long long limitBytes_ = 0, baselineBytes_ = 0;
    std::atomic<long long> refusedBytes_{0};  // Embree's bytes with the first refused allocation; 0: none
    std::mutex errorMutex_;
    std::string firstError_;
    bool native16_ = false, native8_ = false;
};

}  // namespace strahl
