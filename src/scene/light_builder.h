#pragma once
// Internal to the scene module: the scene file's lights as the World's
// lights. Each kind loads what it names: environment images are read here
// (whole, as floats) and become an importance-sampled EnvironmentMap.

#include "strahl/integrator/light.h"
#include "strahl/scene/scene_desc.h"

namespace strahl::scene_detail {

Light buildLight(const LightDesc& desc, const SceneDesc& scene);

}  // namespace strahl::scene_detail
