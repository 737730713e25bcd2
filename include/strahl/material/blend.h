#pragma once
// "blend": (1 - weight) first + weight second, the weighted sum of two
// materials' scattering (Mitsuba's blendbsdf, pbrt's mix; docs/materials.md,
// "Blend"). Bsdf::blend() says how it is evaluated and sampled.
//
//   key        value                                              default
//   materials  [first, second]: two material objects, each a        required
//              "type" with that kind's keys (a blend too); what
//              every material may have (emission, maps, opacity,
//              mapping) belongs on the blend itself
//   weight     in [0, 1]: number or texture ({"texture": ...,       0.5
//              "channel": ...} or a mesh {"attribute": ...})
//
// The two kinds are held through MaterialKindBox (material_kinds.h), which
// completes the recursion MaterialKind -> BlendMaterial -> MaterialKind; the
// members that need it complete are defined there.

#include <array>
#include <memory>
#include <string_view>

#include "strahl/bsdf/bsdf.h"
#include "strahl/material/kind_parsing.h"

namespace strahl {

struct MaterialKindBox;

struct BlendMaterial {
    static constexpr std::string_view kName = "blend";
    static constexpr std::array<std::string_view, 2> kKeys = {"materials", "weight"};

    std::array<std::unique_ptr<MaterialKindBox>, 2> parts;  // never null once parsed
    TexturedFloat weight{0.5f, {}, 0};

    BlendMaterial();
    BlendMaterial(const BlendMaterial& other);
    BlendMaterial(BlendMaterial&&) noexcept;
    BlendMaterial& operator=(const BlendMaterial& other);
    BlendMaterial& operator=(BlendMaterial&&) noexcept;
    ~BlendMaterial();

    template <typename Reader>
    static BlendMaterial parse(const Reader& r) {
        BlendMaterial m;
        r.materialPair("materials", m.parts);
        r.texturedFloat("weight", 0.0f, 1.0f, m.weight);
        return m;
    }
    Bsdf bsdf(const MaterialPoint& p) const;
    template <typename Fn>
    void forEachTexture(Fn&& fn);
};

}  // namespace strahl
