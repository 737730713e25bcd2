#include "light_builder.h"

#include "image_reader.h"
#include "material_builder.h"
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

// What a light kind's load() reads its files through.
class LightResources {
public:
    LightResources(const LightDesc& desc, const SceneDesc& scene, World& world)
        : desc_(desc), scene_(scene), world_(world) {}
    std::shared_ptr<const EnvironmentMap> environmentMap(const std::filesystem::path& file,
                                                         RowLayout rows) const {
        return loadEnvironment(file, rows, desc_, scene_);
    }
    TextureHandle colorTexture(const std::filesystem::path& file) const {
        return addTexture(world_, file, TextureEncoding::Color,
                          scene_.file.filename().string() + ": " + desc_.where);
    }
    glm::ivec2 textureResolution(TextureHandle texture) const {
        return world_.textures->resolution(texture);
    }

private:
    const LightDesc& desc_;
    const SceneDesc& scene_;
    World& world_;
};

}  // namespace

Light buildLight(const LightDesc& desc, const SceneDesc& scene, World& world) {
    Light light = desc.light;
    const LightResources resources(desc, scene, world);
    std::visit([&](auto& kind) { kind.load(resources); }, light.kind);
    return light;
}

}  // namespace strahl::scene_detail
