#include "embree_device.h"

#include <string>

#include "strahl/core/error.h"
#include "strahl/core/process_memory.h"

namespace strahl {

namespace {
const char* errorName(RTCError code) {
    switch (code) {
        case RTC_ERROR_NONE: return "no error";
        case RTC_ERROR_UNKNOWN: return "unknown error";
        case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
        case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
        case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
        case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
        case RTC_ERROR_CANCELLED: return "cancelled";
    }
    return "unrecognised error";
}
}  // namespace

EmbreeDevice::EmbreeDevice(int threads, size_t limitBytes, size_t baselineBytes)
    : limitBytes_(static_cast<long long>(limitBytes)),
      baselineBytes_(static_cast<long long>(baselineBytes)) {
    // Explicit thread count (0 lets Embree use every hardware thread); no thread
    // pinning, since strahl shares the machine with its own oneTBB workers.
    const std::string config = "threads=" + std::to_string(threads > 0 ? threads : 0) +
                               ",set_affinity=0,verbose=0";
    device_ = rtcNewDevice(config.c_str());
    if (!device_) fail("Embree: cannot create a device: ", errorName(rtcGetDeviceError(nullptr)));
    rtcSetDeviceErrorFunction(device_, &EmbreeDevice::onError, this);
    rtcSetDeviceMemoryMonitorFunction(device_, &EmbreeDevice::onMemory, this);
    native16_ = rtcGetDeviceProperty(device_, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED) != 0;
    native8_ = rtcGetDeviceProperty(device_, RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED) != 0;
}

EmbreeDevice::~EmbreeDevice() {
    if (device_) rtcReleaseDevice(device_);
}

void EmbreeDevice::onError(void* self, RTCError code, const char* message) {
    auto* device = static_cast<EmbreeDevice*>(self);
    std::lock_guard lock(device->errorMutex_);
    if (device->firstError_.empty())
        device->firstError_ = std::string(errorName(code)) + (message ? std::string(": ") + message : "");
}

bool EmbreeDevice::onMemory(void* self, ssize_t bytes, bool post) {
    // Called from Embree's build threads, before an allocation (post false) or
    // after one whose size was not known in advance (post true), and with
    // negative bytes when memory is freed. Returning false for an allocation
    // makes Embree stop the API call with RTC_ERROR_OUT_OF_MEMORY; before the
    // allocation that means it never happens (so it is not counted), after it
    // Embree frees it and reports the negative bytes (so it stays counted).
    auto* device = static_cast<EmbreeDevice*>(self);
    const long long held = device->bytes_.fetch_add(bytes, std::memory_order_relaxed) + bytes;
    if (bytes <= 0 || device->limitBytes_ == 0 ||
        device->baselineBytes_ + held <= device->limitBytes_)
        return true;
    if (!post) device->bytes_.fetch_sub(bytes, std::memory_order_relaxed);
    long long none = 0;  // keep the first refusal: later ones follow from it
    device->refusedBytes_.compare_exchange_strong(none, held, std::memory_order_relaxed);
    return false;
}

void EmbreeDevice::check(const char* what) {
    std::string message;
    {
        std::lock_guard lock(errorMutex_);
        message.swap(firstError_);
    }
    const RTCError code = rtcGetDeviceError(device_);
    if (message.empty() && code != RTC_ERROR_NONE) message = errorName(code);
    if (message.empty()) return;
    if (const long long refused = refusedBytes_.load(); refused > 0) {
        fail(what, ": stopped at the memory limit of ", formatBytes(size_t(limitBytes_)),
             ": the scene held ", formatBytes(size_t(baselineBytes_)),
             " when the BVH build started and the BVH needed at least ",
             formatBytes(size_t(refused)),
             " more; raise --memory-limit (and keep compact mode, the leanest BVH: the default "
             "with --memory-limit)");
    }
    fail("Embree: ", what, ": ", message);
}

}  // namespace strahl
