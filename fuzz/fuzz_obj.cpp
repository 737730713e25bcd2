// libFuzzer target: the OBJ loader (loadObjFromMemory) and, after a line "@mtl", the
// .mtl reader (see runObj in fuzz_harness.h).
// Built and run by scripts/fuzz.sh; docs/reliability.md, "Fuzzing".

#include <cstddef>
#include <cstdint>

#include "fuzz_harness.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    strahl::fuzz::expectErrorOrSuccess(strahl::fuzz::runObj, strahl::fuzz::asText(data, size));
    return 0;
}
