// libFuzzer target: the pbrt-v4 scene importer (the language, the mapping,
// then strahl's scene parser on what it makes). docs/pbrt.md; built and run
// by scripts/fuzz.sh (docs/reliability.md, "Fuzzing").

#include <cstddef>
#include <cstdint>

#include "fuzz_harness.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    strahl::fuzz::expectErrorOrSuccess(strahl::fuzz::runPbrt, strahl::fuzz::asText(data, size));
    return 0;
}
