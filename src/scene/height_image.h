#pragma once
// Internal to the scene module: a grey image read as a grid of heights for
// makeHeightField (geometry/height_field.h).

#include <filesystem>
#include <vector>

namespace strahl::scene_detail {

struct HeightImage {
    std::vector<float> heights;  // row-major, columns × rows
    int columns = 0;
    int rows = 0;
};

// Reads any image OpenImageIO can (PNG, EXR, TIFF, ...). The height of a pixel
// is its first channel, or for three or more channels the Rec. 709 luminance
// 0.2126 R + 0.7152 G + 0.0722 B of the first three. Values are taken as
// stored, with no colour conversion: float formats as they are, integer
// formats normalised to [0, 1] (8-bit 255 → 1.0). Row 0 is the image's TOP
// row, which makeHeightField puts at the +y edge; column 0 is the left (−x)
// edge. Throws strahl::Error naming the file if it is missing, not a readable
// image, a volume, larger than 2^26 pixels, or holds a non-finite value.
HeightImage loadHeightImage(const std::filesystem::path& file);

}  // namespace strahl::scene_detail
