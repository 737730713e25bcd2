#include "light_builder.h"

#include <glm/gtc/matrix_transform.hpp>

#include "image_reader.h"
#include "strahl/core/error.h"

namespace strahl::scene_detail {

namespace {

// 16384 x 8192: the largest lat-long maps in common use (16K HDRIs), 1.5 GiB
// of floats; anything larger is more likely a corrupt header.
constexpr size_t kMaxEnvironmentPixels = size_t(1) << 27;

std::shared_ptr<const EnvironmentMap> loadEnvironment(const LightDesc& desc,
                                                      const SceneDesc& scene) {
    try {
        const FloatImage image = readFloatImage(desc.file, "environment image",
                                                kMaxEnvironmentPixels);
        std::vector<Color> texels(static_cast<size_t>(image.width) *
                                  static_cast<size_t>(image.height));
        for (size_t k = 0; k < texels.size(); ++k) {
            const float* p = &image.pixels[k * static_cast<size_t>(image.channels)];
            texels[k] = image.channels == 3 ? Color(p[0], p[1], p[2]) : Color(p[0]);
        }
        return std::make_shared<EnvironmentMap>(image.width, image.height, std::move(texels));
    } catch (const Error& e) {
        fail(scene.file.filename().string(), ": ", desc.where, ": ", e.what());
    }
}

}  // namespace

Light buildLight(const LightDesc& d, const SceneDesc& scene) {
    Light light;
    light.position = d.position;
    light.direction = d.direction;
    light.intensity = d.intensity;
    light.irradiance = d.irradiance;
    switch (d.type) {
        case LightType::Point: light.type = Light::Type::Point; break;
        case LightType::Spot:
            light.type = Light::Type::Spot;
            light.cosTotalWidth = std::cos(glm::radians(d.coneAngle));
            light.cosFalloffStart = std::cos(glm::radians(d.falloffStart));
            break;
        case LightType::Directional:
            light.type = Light::Type::Directional;
            light.angularRadius = glm::radians(0.5f * d.angularDiameter);
            break;
        case LightType::Environment: {
            light.type = Light::Type::Environment;
            light.environment = loadEnvironment(d, scene);
            light.scale = d.scale;
            // World to map space: the inverse of the map's rotation about +y.
            light.worldToEnvironment =
                Mat3(glm::rotate(Mat4(1.0f), glm::radians(-d.rotation), Vec3(0.0f, 1.0f, 0.0f)));
            break;
        }
        case LightType::Sky:
            light.type = Light::Type::Sky;
            light.radiance = d.radiance;
            break;
    }
    return light;
}

}  // namespace strahl::scene_detail
