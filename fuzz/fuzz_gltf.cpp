// libFuzzer target: the glTF 2.0 loader (loadGltfFromMemory): .gltf JSON with data-URI
// buffers, or a binary .glb.
// Built and run by scripts/fuzz.sh; docs/reliability.md, "Fuzzing".

#include <cstddef>
#include <cstdint>

#include "fuzz_harness.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    strahl::fuzz::expectErrorOrSuccess(strahl::fuzz::runGltf, strahl::fuzz::asText(data, size));
    return 0;
}
