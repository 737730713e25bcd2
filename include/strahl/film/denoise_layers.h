#pragma once
// The EXR layers a denoised render carries (docs/denoising.md, docs/output.md):
//   R, G, B                        the denoised beauty (the main image)
//   noisy.R, noisy.G, noisy.B      the beauty as rendered
//   half0.R .. half0.B             beauty of the even samples       } written whenever
//   half0.albedo.R .. .B           their albedo, normal, depth      } the film keeps
//   half0.normal.X .. .Z, half0.depth.Z                             } the halves
//   half1.*                        the same for the odd samples     } (--denoise)
// `strahl denoise` reads the half layers and the variance AOV back.

#include <string>
#include <string_view>
#include <vector>

#include "strahl/film/film.h"

namespace strahl {

// "half0" or "half1".
std::string halfLayerName(int half);

// The channels of one half in file order of appendHalfLayers: "half0.R",
// ..., "half0.albedo.R", ..., "half0.normal.X", ..., "half0.depth.Z".
std::vector<std::string> halfLayerChannels(int half);

// Whether a channel belongs to the layers above (noisy.*, half0.*, half1.*).
bool isDenoiseLayerChannel(std::string_view channel);

// Appends both halves' layers of a film that keeps them (crop-sized planes,
// interleaved by layer: RGB beauty, RGB albedo, XYZ normal, Z depth).
void appendHalfLayers(const Film& film, std::vector<std::string>& names,
                      std::vector<std::vector<float>>& planes);

}  // namespace strahl
