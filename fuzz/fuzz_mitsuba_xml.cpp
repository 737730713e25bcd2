// libFuzzer target: the Mitsuba 3 scene importer (XML language, plugins, then
// strahl's scene parser on what it makes). docs/mitsuba.md; built and run by
// scripts/fuzz.sh (docs/reliability.md, "Fuzzing").

#include <cstddef>
#include <cstdint>

#include "fuzz_harness.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    strahl::fuzz::expectErrorOrSuccess(strahl::fuzz::runMitsubaXml,
                                       strahl::fuzz::asText(data, size));
    return 0;
}
