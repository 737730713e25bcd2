#pragma once
// Internal to the scene module: reads a whole image through OpenImageIO as
// floats, for the images the scene builder turns into data (height fields,
// environment maps). Textures are different: they go through the texture
// system, tiled and cached (texture/texture_system.h).

#include <filesystem>
#include <vector>

namespace strahl::scene_detail {

struct FloatImage {
    int width = 0, height = 0;
    int channels = 0;           // 1 or 3
    std::vector<float> pixels;  // row-major from the top row, channels interleaved
    // Stored as integers (8 or 16 bits), normalised: the texture system
    // decodes such colour images from sRGB (texture_system.h).
    bool integer = false;
};

// Reads the first channel of a one- or two-channel image, else the first
// three. Values as stored: float formats unchanged, integer formats normalised
// to [0, 1], no colour conversion and no alpha premultiplication. `what` names
// the image's role in errors ("height image"). Throws strahl::Error naming the
// file if it is missing, not a readable image, a volume, larger than
// maxPixels, or holds a non-finite value.
FloatImage readFloatImage(const std::filesystem::path& file, const char* what, size_t maxPixels);

}  // namespace strahl::scene_detail
