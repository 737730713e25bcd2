#pragma once
// Shared by the CLI tests: the scene files they render.

#include <string>

#include "test_support.h"

namespace strahl::test {

// scenes/default.json, the scene of a plain `strahl render`.
inline const std::string kDefaultScene = (sourceDir() / "scenes/default.json").string();

// Path tracing with glass, metals, implicit and parametric shapes and every
// other geometry kind (long, varied paths), small enough for tests.
inline const std::string kGlossyRoom =
    (sourceDir() / "scenes/statistical/glossy_room.json").string();

}  // namespace strahl::test
