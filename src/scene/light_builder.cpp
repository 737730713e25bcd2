#include "light_builder.h"

#include "image_reader.h"
#include "strahl/core/error.h"

namespace strahl::scene_detail {

namespace {

// 16384 x 8192: the largest lat-long maps in common use (16K HDRIs), 1.5 GiB
// of floats; anything larger is more likely a corrupt header.
constexpr size_t kMaxEnvironmentPixels = size_t(1) << 27;

std::shared_ptr<const EnvironmentMap> loadEnvironment(const std::filesystem::path& file,
                                                      RowLayout rows, const LightDesc& desc,
                                                      const SceneDesc& scene) {
    try {
        const FloatImage image = readFloatImage(file, "environment image",
                                                kMaxEnvironmentPixels);
        std::vector<Color> texels(static_cast<size_t>(image.width) *
                                  static_cast<size_t>(image.height));
        for (size_t k = 0; k < texels.size(); ++k) {
            const float* p = &image.pixels[k * static_cast<size_t>(image.channels)];
            texels[k] = image.channels == 3 ? Color(p[0], p[1], p[2]) : Color(p[0]);
        }
        return std::make_shared<EnvironmentMap>(image.width, image.height, std::move(texels), rows);
    } catch (const Error& e) {
        fail(scene.file.filename().string(), ": ", desc.where, ": ", e.what());
    }
}

}  // namespace

Light buildLight(const LightDesc& desc, const SceneDesc& scene) {
    Light light = desc.light;
    std::visit(
        [&](auto& kind) {
            kind.load([&](const std::filesystem::path& file, RowLayout rows) {
                return loadEnvironment(file, rows, desc, scene);
            });
        },
        light.kind);
    return light;
}

}  // namespace strahl::scene_detail
