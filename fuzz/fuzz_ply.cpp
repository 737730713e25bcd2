// libFuzzer target: the PLY loader (loadPlyFromMemory): the header, then an ascii,
// binary_little_endian or binary_big_endian body.
// Built and run by scripts/fuzz.sh; docs/reliability.md, "Fuzzing".

#include <cstddef>
#include <cstdint>

#include "fuzz_harness.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    strahl::fuzz::expectErrorOrSuccess(strahl::fuzz::runPly, strahl::fuzz::asText(data, size));
    return 0;
}
