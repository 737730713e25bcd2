// libFuzzer target: the Mitsuba serialized loader (loadSerializedFromMemory):
// the header, the end-of-file dictionary and the zlib stream, for the first
// and the second mesh of each input.
// Built and run by scripts/fuzz.sh; docs/reliability.md, "Fuzzing".

#include <cstddef>
#include <cstdint>

#include "fuzz_harness.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    strahl::fuzz::expectErrorOrSuccess(strahl::fuzz::runSerialized, strahl::fuzz::asText(data, size));
    return 0;
}
