#pragma once
// Internal to the scene module: errors found after parsing, when a file a
// scene value names is read, worded as the parser words its own:
// "<scene file>: <pointer>: <message>", followed by " (set by <origins>)"
// when command-line patches set that value or one around it.

#include <string>
#include <utility>
#include <vector>

#include "strahl/scene/scene_desc.h"

namespace strahl::scene_detail {

// The origins ("--spp 4, --set /a=1") of the patches at `pointer`, inside it
// or above it; "" if none or if `pointer` is the top level.
std::string patchOrigins(const std::vector<std::pair<std::string, std::string>>& patches,
                         const std::string& pointer);

[[noreturn]] void failAt(const SceneDesc& desc, const ScenePlace& at, const std::string& message);

}  // namespace strahl::scene_detail
