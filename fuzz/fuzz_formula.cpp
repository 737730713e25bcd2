// libFuzzer target: the formula compiler (Formula::compile), and the compiled tape
// evaluated in double, interval and dual arithmetic (see runFormula in
// fuzz_harness.h for the input format).
// Built and run by scripts/fuzz.sh; docs/reliability.md, "Fuzzing".

#include <cstddef>
#include <cstdint>

#include "fuzz_harness.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    strahl::fuzz::expectErrorOrSuccess(strahl::fuzz::runFormula, strahl::fuzz::asText(data, size));
    return 0;
}
