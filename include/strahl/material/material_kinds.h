#pragma once
// The closed set of material kinds: one header per kind, each with its keys
// and defaults, its parsing, its BSDF and its textures (see diffuse.h for the
// shape every kind has). To add a kind, write its header and add it to this
// list: the scene parser, the texture binding and the BSDF construction all
// visit this variant, so the compiler finds every place that must handle it.
// The order is the order `type` errors list the names in.

#include <variant>

#include "strahl/core/closed_family.h"
#include "strahl/material/conductor.h"
#include "strahl/material/dielectric.h"
#include "strahl/material/diffuse.h"
#include "strahl/material/emissive.h"
#include "strahl/material/metallic_roughness.h"
#include "strahl/material/phong.h"
#include "strahl/material/plastic.h"
#include "strahl/material/thin_dielectric.h"

namespace strahl {

using MaterialKind =
    std::variant<DiffuseMaterial, PhongMaterial, BlinnMaterial, ConductorMaterial,
                 DielectricMaterial, ThinDielectricMaterial, PlasticMaterial,
                 MetallicRoughnessMaterial, EmissiveMaterial>;

}  // namespace strahl
