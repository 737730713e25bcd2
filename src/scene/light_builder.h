#pragma once
// Internal to the scene module: the scene file's lights as the World's
// lights. Each kind loads what it names: environment images are read here
// (whole, as floats) and become an importance-sampled EnvironmentMap; a
// spot's projected image joins the world's texture system.

#include "strahl/integrator/light.h"
#include "strahl/integrator/world.h"
#include "strahl/scene/scene_desc.h"

namespace strahl::scene_detail {

Light buildLight(const LightDesc& desc, const SceneDesc& scene, World& world);

}  // namespace strahl::scene_detail
