#include "light_builder.h"

#include <cmath>

#include "image_reader.h"
#include "material_builder.h"
#include "strahl/core/equal_area.h"
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

// A square image in pbrt-v4's equal-area octahedral layout resampled into a
// lat-long map (environment_map.h) of twice its side by its side: each
// lat-long texel centre's direction d, taken to the image's frame by
// mapFromWorld, is looked up bilinearly in the square (texel values at their
// centres; across an edge the square folds onto itself as the octahedron
// does, so lookups are continuous over the sphere).
std::shared_ptr<const EnvironmentMap> loadEqualArea(const std::filesystem::path& file, const Mat3& mapFromWorld,
                                                    const LightDesc& desc, const SceneDesc& scene) {
    try {
        const FloatImage image = readFloatImage(file, "environment image", kMaxEnvironmentPixels / 2);
        if (image.width != image.height)
            fail(file.string(), ": an equal-area map must be square, got ", image.width, " x ", image.height);
        const int n = image.width;
        auto texel = [&](int x, int y) {
            // The octahedral fold: leaving the square across an edge comes
            // back mirrored along that edge.
            if (x < 0) x = -x - 1, y = n - 1 - y;
            else if (x >= n) x = 2 * n - 1 - x, y = n - 1 - y;
            if (y < 0) y = -y - 1, x = n - 1 - x;
            else if (y >= n) y = 2 * n - 1 - y, x = n - 1 - x;
            const float* p = &image.pixels[(size_t(y) * size_t(n) + size_t(x)) * size_t(image.channels)];
            return image.channels >= 3 ? Color(p[0], p[1], p[2]) : Color(p[0]);
        };
        const int width = 2 * n, height = n;
        const float side = static_cast<float>(n);
        std::vector<Color> texels(size_t(width) * size_t(height));
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                const Vec3 d = EnvironmentMap::direction(Vec2((static_cast<float>(x) + 0.5f) / (2.0f * side),
                                                              (static_cast<float>(y) + 0.5f) / side));
                const Vec2 uv = equalAreaSphereToSquare(glm::normalize(mapFromWorld * d));
                // Row 0 of the image is v = 0 (pbrt reads the square as stored).
                const float fx = uv.x * side - 0.5f, fy = uv.y * side - 0.5f;
                const int x0 = static_cast<int>(std::floor(fx)), y0 = static_cast<int>(std::floor(fy));
                const float tx = fx - static_cast<float>(x0), ty = fy - static_cast<float>(y0);
                texels[size_t(y) * size_t(width) + size_t(x)] =
                    (1 - tx) * (1 - ty) * texel(x0, y0) + tx * (1 - ty) * texel(x0 + 1, y0) +
                    (1 - tx) * ty * texel(x0, y0 + 1) + tx * ty * texel(x0 + 1, y0 + 1);
            }
        return std::make_shared<EnvironmentMap>(width, height, std::move(texels), RowLayout::Centred);
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
    std::shared_ptr<const EnvironmentMap> equalAreaMap(const std::filesystem::path& file,
                                                       const Mat3& mapFromWorld) const {
        return loadEqualArea(file, mapFromWorld, desc_, scene_);
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
