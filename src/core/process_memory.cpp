#include "strahl/core/process_memory.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>

#include "strahl/core/error.h"

namespace strahl {

namespace {

// The value of a "<key>:   1234 kB" line of /proc/self/status, in bytes.
size_t statusField(const char* key) {
    std::ifstream in("/proc/self/status");
    std::string line;
    const size_t keyLength = std::strlen(key);
    while (std::getline(in, line)) {
        if (line.compare(0, keyLength, key) != 0 || line.size() <= keyLength ||
            line[keyLength] != ':')
            continue;
        unsigned long long kib = 0;
        if (std::sscanf(line.c_str() + keyLength + 1, "%llu", &kib) != 1) return 0;
        return static_cast<size_t>(kib) * 1024;  // the kernel's "kB" is KiB
    }
    return 0;
}

}  // namespace

size_t residentBytes() { return statusField("VmRSS"); }
size_t peakResidentBytes() { return statusField("VmHWM"); }

std::string formatBytes(size_t bytes) {
    static const char* const kUnits[] = {"KiB", "MiB", "GiB", "TiB"};
    if (bytes < 1024) return std::to_string(bytes) + " B";
    double value = static_cast<double>(bytes) / 1024.0;
    size_t unit = 0;
    while (value >= 1024.0 && unit + 1 < std::size(kUnits)) {
        value /= 1024.0;
        ++unit;
    }
    char buf[32];
    std::snprintf(buf, sizeof buf, value < 10.0 ? "%.2f %s" : "%.1f %s", value, kUnits[unit]);
    return buf;
}

size_t parseByteSize(const std::string& text, const std::string& what) {
    const auto bad = [&](const char* why) {
        fail(what, ": '", text, "' ", why,
             " (expected a size such as 8G, 512M, 1.5G or a number of bytes)");
    };
    double value = 0.0;
    int used = 0;
    if (std::sscanf(text.c_str(), "%lf%n", &value, &used) != 1 || !std::isfinite(value))
        bad("is not a size");
    std::string suffix = text.substr(static_cast<size_t>(used));
    for (char& c : suffix) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    int shift = 0;  // the suffix's power of 2
    if (!suffix.empty()) {
        const std::string letters = "KMGT";
        const size_t at = letters.find(suffix[0]);
        if (at == std::string::npos) {
            if (suffix != "B") bad("has an unknown unit");
        } else {
            shift = 10 * static_cast<int>(at + 1);
            const std::string rest = suffix.substr(1);
            if (!rest.empty() && rest != "B" && rest != "IB") bad("has an unknown unit");
        }
    }
    const double bytes = std::ldexp(value, shift);
    if (!(bytes >= 1.0)) bad("is not a positive size");
    if (bytes > std::ldexp(1.0, 60)) bad("is more than 2^60 bytes");
    return static_cast<size_t>(bytes);
}

}  // namespace strahl
