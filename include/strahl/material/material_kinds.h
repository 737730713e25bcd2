#pragma once
// The closed set of material kinds: one header per kind, each with its keys
// and defaults, its parsing, its BSDF and its textures (see diffuse.h for the
// shape every kind has). To add a kind, write its header and add it to this
// list: the scene parser, the texture binding and the BSDF construction all
// visit this variant, so the compiler finds every place that must handle it.
// The order is the order `type` errors list the names in.

#include <variant>

#include "strahl/core/closed_family.h"
#include "strahl/material/blend.h"
#include "strahl/material/coated_conductor.h"
#include "strahl/material/conductor.h"
#include "strahl/material/dielectric.h"
#include "strahl/material/diffuse.h"
#include "strahl/material/diffuse_transmission.h"
#include "strahl/material/emissive.h"
#include "strahl/material/hair.h"
#include "strahl/material/metallic_roughness.h"
#include "strahl/material/phong.h"
#include "strahl/material/plastic.h"
#include "strahl/material/principled.h"
#include "strahl/material/thin_dielectric.h"

namespace strahl {

using MaterialKind =
    std::variant<DiffuseMaterial, PhongMaterial, BlinnMaterial, ConductorMaterial,
                 DielectricMaterial, ThinDielectricMaterial, DiffuseTransmissionMaterial, PlasticMaterial,
                 CoatedConductorMaterial,
                 MetallicRoughnessMaterial, PrincipledMaterial, HairMaterial, BlendMaterial, EmissiveMaterial>;

// A material kind held by pointer (BlendMaterial's parts).
struct MaterialKindBox {
    MaterialKind kind;
};

inline BlendMaterial::BlendMaterial() = default;
inline BlendMaterial::BlendMaterial(BlendMaterial&&) noexcept = default;
inline BlendMaterial& BlendMaterial::operator=(BlendMaterial&&) noexcept = default;
inline BlendMaterial::~BlendMaterial() = default;
// Copies are deep: binding a copy's textures leaves the original as it was.
inline BlendMaterial::BlendMaterial(const BlendMaterial& other) : weight(other.weight) {
    for (size_t i = 0; i < parts.size(); ++i)
        if (other.parts[i]) parts[i] = std::make_unique<MaterialKindBox>(*other.parts[i]);
}
inline BlendMaterial& BlendMaterial::operator=(const BlendMaterial& other) {
    if (this != &other) *this = BlendMaterial(other);
    return *this;
}

inline Bsdf BlendMaterial::bsdf(const MaterialPoint& p) const {
    const auto of = [&](const MaterialKindBox& part) {
        return std::visit([&](const auto& kind) { return kind.bsdf(p); }, part.kind);
    };
    return Bsdf::blend(of(*parts[0]), of(*parts[1]), p.unit(weight));
}

template <typename Fn>
void BlendMaterial::forEachTexture(Fn&& fn) {
    for (const std::unique_ptr<MaterialKindBox>& part : parts)
        std::visit([&](auto& kind) { kind.forEachTexture(fn); }, part->kind);
    visitTextures(weight, TextureEncoding::Data, fn);
}

}  // namespace strahl
