// The list of built-in implicit kinds (implicit_kinds.h). A new kind: its file
// src/geometry/implicit_<kind>.cpp defines `const ImplicitKind kImplicit<Kind>`
// and one line below names it.

#include "strahl/geometry/implicit_kinds.h"

namespace strahl {

extern const ImplicitKind kImplicitSphere, kImplicitQuadric, kImplicitTorus,
    kImplicitSuperellipsoid, kImplicitBlobs, kImplicitPeriodic;

namespace {

const ImplicitKind* const kImplicitKinds[] = {
    &kImplicitSphere,         //
    &kImplicitQuadric,        //
    &kImplicitTorus,          //
    &kImplicitSuperellipsoid, //
    &kImplicitBlobs,          //
    &kImplicitPeriodic,       // gyroid, schwarz_p, schwarz_d, neovius
};

}  // namespace

std::span<const ImplicitKind* const> implicitKinds() {
    return kImplicitKinds;
}

const ImplicitKind* findImplicitKind(std::string_view name) {
    return findKindNamed(implicitKinds(), name);
}

}  // namespace strahl
