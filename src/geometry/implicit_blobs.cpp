// "blobs": metaballs with the compact soft-object kernel of Wyvill et al.
// (1986), f = threshold − Σ strength·(1 − ‖x − c‖²/R²)³.
// docs/implicit-surfaces.md has the derivations.
//
//   key         value                                              default
//   blobs       [{center, radius > 0, strength}, ...], at least one   required
//   threshold   > 0                                                 0.5

#include <array>
#include <memory>
#include <string_view>
#include <vector>

#include "implicit_builtin.h"

namespace strahl::implicit_detail {

class Blobs final : public ImplicitSurfaceOf<Blobs> {
public:
    Blobs(std::vector<Blob> blobs, double threshold)
        : blobs_(std::move(blobs)), threshold_(threshold) {}

    template <class T>
    T eval(const Point3<T>& p) const {
        T field(0.0);
        for (const Blob& b : blobs_) {
            const T q = (sqr(p.x - b.center.x) + sqr(p.y - b.center.y) + sqr(p.z - b.center.z)) *
                        (1.0 / (b.radius * b.radius));
            field += b.strength * powi(max(T(0.0), 1.0 - q), 3);
        }
        return threshold_ - field;
    }
    DVec3 gradient(const DVec3& x) const override {
        // ∇(s (1 − ‖x−c‖²/R²)³) = −6 s (1 − q)² (x − c)/R², negated by f = T − Σ.
        DVec3 g(0.0);
        for (const Blob& b : blobs_) {
            const DVec3 rel = x - b.center;
            const double w = 1.0 - glm::dot(rel, rel) / (b.radius * b.radius);
            if (w > 0.0) g += 6.0 * b.strength * w * w / (b.radius * b.radius) * rel;
        }
        return g;
    }
    std::optional<Bounds3> bounds() const override {
        // Outside every ball the field is 0 and f = threshold > 0.
        Bounds3 box;
        for (const Blob& b : blobs_) {
            box.expand(Vec3(b.center - b.radius));
            box.expand(Vec3(b.center + b.radius));
        }
        return box;
    }
    std::string describe() const override {
        return concat("blobs n=", blobs_.size(), " threshold=", threshold_);
    }

private:
    std::vector<Blob> blobs_;
    double threshold_;
};

}  // namespace strahl::implicit_detail

namespace strahl {

ImplicitSurfacePtr makeBlobs(std::vector<Blob> blobs, double threshold) {
    if (blobs.empty()) fail("blobs need at least one blob");
    implicit_detail::requirePositive("threshold", threshold);
    for (const Blob& b : blobs) {
        implicit_detail::requireFinite("center", b.center.x);
        implicit_detail::requireFinite("center", b.center.y);
        implicit_detail::requireFinite("center", b.center.z);
        implicit_detail::requirePositive("radius", b.radius);
        implicit_detail::requireFinite("strength", b.strength);
    }
    return std::make_shared<implicit_detail::Blobs>(std::move(blobs), threshold);
}

namespace {

ImplicitSurfacePtr parseImplicitBlobs(const SurfaceParameters& p) {
    p.requireKeys({"type", "transform", "threshold", "blobs"});
    const auto list = p.child("blobs");
    std::vector<Blob> blobs;
    for (size_t i = 0; i < list->size(); ++i) {
        const auto b = list->at(i);
        b->requireKeys({"center", "radius", "strength"});
        Blob blob;
        blob.center = b->vec3("center", blob.center);
        blob.radius = b->number("radius", 1.0);
        blob.strength = b->number("strength", 1.0);
        blobs.push_back(blob);
    }
    const double threshold = p.number("threshold", 0.5);
    return p.checked([&] { return makeBlobs(std::move(blobs), threshold); });
}

constexpr std::array<std::string_view, 1> kImplicitBlobsNames = {"blobs"};

}  // namespace

extern const ImplicitKind kImplicitBlobs;
const ImplicitKind kImplicitBlobs{kImplicitBlobsNames, &parseImplicitBlobs};

}  // namespace strahl
