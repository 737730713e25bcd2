#pragma once
// The memory this process holds, as the kernel counts it (Linux
// /proc/self/status): what render summaries, `strahl info` and --memory-limit
// report and check. Resident memory is what a machine runs out of; it
// includes the meshes, the BVH, textures and the film, not the parts of
// mapped files the process never touched.

#include <cstddef>
#include <string>

namespace strahl {

// VmRSS: resident now; 0 if the kernel does not say (not Linux).
size_t residentBytes();
// VmHWM: the peak resident memory since the process started; 0 if unknown.
size_t peakResidentBytes();

// "1.25 GiB", "310.4 MiB", "12.0 KiB" or "512 B" (binary units, as the
// --memory-limit suffixes).
std::string formatBytes(size_t bytes);

// "8G", "512M", "1.5G", "64K", "1T" or a plain byte count: binary units
// (K = 2^10 ...), an optional "iB"/"B" after the letter. Throws strahl::Error
// "<what>: ..." for anything else, for zero, and for more than 2^60 bytes.
size_t parseByteSize(const std::string& text, const std::string& what);

}  // namespace strahl
