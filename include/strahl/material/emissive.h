#pragma once
// "emissive": emits (the material's "emission", required) and reflects
// nothing. Any other material may emit too.

#include <array>
#include <string_view>

#include "strahl/bsdf/bsdf.h"
#include "strahl/material/kind_parsing.h"

namespace strahl {

struct EmissiveMaterial {
    static constexpr std::string_view kName = "emissive";
    static constexpr std::array<std::string_view, 0> kKeys = {};

    template <typename Reader>
    static EmissiveMaterial parse(const Reader& r) {
        if (!r.has("emission")) r.fail("an emissive material needs 'emission'");
        return {};
    }
    Bsdf bsdf(const MaterialPoint&) const { return Bsdf::black(); }
    template <typename Fn>
    void forEachTexture(Fn&&) {}
};

}  // namespace strahl
