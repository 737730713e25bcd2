#pragma once
// strahl's built-in OpenColorIO config, used when neither --ocio-config nor
// $OCIO names one. Internal to the film module.

#include <OpenColorIO/OpenColorIO.h>

namespace strahl::detail {

// Built through the OCIO C++ API (no files) on first use and shared afterwards:
//   colour spaces  "Linear Rec.709" (reference; roles scene_linear, default, ...),
//                  "sRGB Encoded Rec.709", "Filmic sRGB", "Raw" (data)
//   display "sRGB" with views "Standard" (default), "Filmic", "Raw".
OCIO_NAMESPACE::ConstConfigRcPtr builtinColorConfig();

}  // namespace strahl::detail
