// libFuzzer target: the scene file parser (parseSceneText): JSON with comments, then every
// key of docs/scene-format.md, formulas and groups included.
// Built and run by scripts/fuzz.sh; docs/reliability.md, "Fuzzing".

#include <cstddef>
#include <cstdint>

#include "fuzz_harness.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    strahl::fuzz::expectErrorOrSuccess(strahl::fuzz::runSceneJson,
                                       strahl::fuzz::asText(data, size));
    return 0;
}
