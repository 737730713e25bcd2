#pragma once
// Comparing a render with a reference the way Mitsuba 3's render tests do
// (../shared/data/mitsuba-tests/SOURCE.txt): a per-pixel, per-channel z-test
// of the rendered mean against the reference mean, using the reference's
// per-sample variance, in CIE XYZ.
//
// Both means and the variance are converted from linear Rec. 709 RGB to XYZ
// with the same 3x3 matrix (Mitsuba converts the variance image as an image
// too). For every pixel and XYZ channel
//
//     z = |mean - reference| · sqrt(spp / max(variance, 1e-4))
//
// and the two-sided p-value is erfc(z / √2). With a significance of 0.01
// over N pixels, the Šidák-corrected level is α = 1 − (1 − 0.01)^(1/N); a
// value passes when p > α, and the image passes when at least 99.75 % of its
// 3N values pass.

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace strahl {

// An RGB image, interleaved, row by row from the top left.
struct RgbImage {
    int width = 0, height = 0;
    std::vector<float> rgb;
};

// The R, G and B channels of an image file (EXR, or anything OpenImageIO
// reads; the channels named R, G, B, else the first three). Throws
// strahl::Error naming the file if it cannot be read or has fewer than three
// channels.
RgbImage readRgbImage(const std::filesystem::path& file);

struct ZTestOptions {
    double significance = 0.01;      // the family-wise level, before Šidák's correction
    double requiredFraction = 0.9975;  // of the values that must pass
    double minVariance = 1e-4;       // the variance floor of Mitsuba's test
};

struct ZTestValue {
    int x = 0, y = 0, channel = 0;  // channel 0, 1, 2: X, Y, Z
    double mean = 0, reference = 0, z = 0, p = 1;
};

struct ZTestResult {
    size_t values = 0, passing = 0;
    double alpha = 0;  // the per-value level p must exceed
    bool passed = false;
    std::vector<float> z;             // per pixel and XYZ channel, interleaved
    std::vector<ZTestValue> worst;    // the smallest p-values, at most 10, smallest first
    double passingFraction() const { return values ? double(passing) / double(values) : 0.0; }
    // "99.91 % of 6912 values pass (need 99.75 %); worst: (12, 30) Y mean 0.52 ref 0.41 p 3e-9, ..."
    std::string summary() const;
};

// Throws strahl::Error if the three images differ in size or spp <= 0.
ZTestResult zTest(const RgbImage& mean, double spp, const RgbImage& reference,
                  const RgbImage& referenceVariance, const ZTestOptions& options = {});

// An EXR showing where the test fails: the mean and reference (RGB), the z
// value of each XYZ channel and a mask that is 1 where any channel fails.
// Written through a temporary name, like every strahl output.
void writeZTestImage(const std::filesystem::path& file, const RgbImage& mean,
                     const RgbImage& reference, const ZTestResult& result);

}  // namespace strahl
