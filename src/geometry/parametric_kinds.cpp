// The list of built-in parametric kinds (parametric_kinds.h). A new kind: its
// file src/geometry/parametric_<kind>.cpp defines
// `const ParametricKind kParametric<Kind>` and one line below names it.

#include "strahl/geometry/parametric_kinds.h"

namespace strahl {

extern const ParametricKind kParametricSphere, kParametricTorus, kParametricCylinder,
    kParametricCone, kParametricMobius;

namespace {

const ParametricKind* const kParametricKinds[] = {
    &kParametricSphere,    //
    &kParametricTorus,     //
    &kParametricCylinder,  //
    &kParametricCone,      //
    &kParametricMobius,    //
};

}  // namespace

std::span<const ParametricKind* const> parametricKinds() {
    return kParametricKinds;
}

const ParametricKind* findParametricKind(std::string_view name) {
    return findKindNamed(parametricKinds(), name);
}

}  // namespace strahl
