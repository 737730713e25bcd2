#include "embree_device.h"

#include <string>

#include "strahl/core/error.h"

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

EmbreeDevice::EmbreeDevice(int threads) {
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

bool EmbreeDevice::onMemory(void* self, ssize_t bytes, bool /*post*/) {
    // Only accounting: returning false would make Embree fail the allocation.
    static_cast<EmbreeDevice*>(self)->bytes_.fetch_add(bytes, std::memory_order_relaxed);
    return true;
}

void EmbreeDevice::check(const char* what) {
    std::string message;
    {
        std::lock_guard lock(errorMutex_);
        message.swap(firstError_);
    }
    const RTCError code = rtcGetDeviceError(device_);
    if (message.empty() && code != RTC_ERROR_NONE) message = errorName(code);
    if (!message.empty()) fail("Embree: ", what, ": ", message);
}

}  // namespace strahl
