#include "strahl/geometry/implicit_csg.h"

#include <cmath>
#include <utility>

#include <glm/matrix.hpp>

#include "strahl/core/error.h"

namespace strahl {

namespace {

using num::abs;
using num::max;
using num::min;
using num::sqr;

class Csg final : public ImplicitSurfaceOf<Csg> {
public:
    Csg(CsgOperation op, std::vector<ImplicitSurfacePtr> operands, double blend)
        : op_(op), operands_(std::move(operands)), k_(blend) {}

    template <class T>
    T eval(const Point3<T>& p) const {
        T result = operands_[0]->evaluate(p);
        for (size_t i = 1; i < operands_.size(); ++i) {
            const T f = operands_[i]->evaluate(p);
            switch (op_) {
            case CsgOperation::Union:
                result = min(result, f);
                break;
            case CsgOperation::Intersection:
                result = max(result, f);
                break;
            case CsgOperation::Difference:
                result = max(result, -f);
                break;
            case CsgOperation::SmoothUnion: {
                const T h = max(T(0.0), k_ - abs(result - f)) * (1.0 / k_);
                result = min(result, f) - sqr(h) * (0.25 * k_);
                break;
            }
            }
        }
        return result;
    }

    std::optional<Bounds3> bounds() const override {
        switch (op_) {
        case CsgOperation::Union:
        case CsgOperation::SmoothUnion: {
            Bounds3 box;
            for (const ImplicitSurfacePtr& f : operands_) {
                const std::optional<Bounds3> b = f->bounds();
                if (!b) return std::nullopt;
                box.expand(*b);
            }
            if (op_ == CsgOperation::SmoothUnion) {
                box.min -= Vec3(static_cast<float>(k_));
                box.max += Vec3(static_cast<float>(k_));
            }
            return box;
        }
        case CsgOperation::Intersection: {
            std::optional<Bounds3> box;
            for (const ImplicitSurfacePtr& f : operands_) {
                const std::optional<Bounds3> b = f->bounds();
                if (!b) continue;
                if (!box) {
                    box = b;
                } else {
                    box->min = glm::max(box->min, b->min);
                    box->max = glm::min(box->max, b->max);
                }
            }
            return box;
        }
        case CsgOperation::Difference:
            return operands_[0]->bounds();
        }
        return std::nullopt;
    }

    std::string describe() const override {
        static const char* names[] = {"union", "intersection", "difference", "smooth_union"};
        std::string text = concat(names[static_cast<int>(op_)], "(");
        for (size_t i = 0; i < operands_.size(); ++i)
            text += (i ? ", " : "") + operands_[i]->describe();
        return text + ")";
    }

private:
    CsgOperation op_;
    std::vector<ImplicitSurfacePtr> operands_;
    double k_;
};

class Transformed final : public ImplicitSurfaceOf<Transformed> {
public:
    Transformed(ImplicitSurfacePtr surface, const glm::dmat4& placement)
        : surface_(std::move(surface)), placement_(placement), inverse_(glm::inverse(placement)) {}

    template <class T>
    T eval(const Point3<T>& p) const {
        // q = M⁻¹ p, written out so that it works for every scalar type T.
        const glm::dmat4& m = inverse_;
        return surface_->evaluate(Point3<T>{
            m[0][0] * p.x + m[1][0] * p.y + m[2][0] * p.z + m[3][0],
            m[0][1] * p.x + m[1][1] * p.y + m[2][1] * p.z + m[3][1],
            m[0][2] * p.x + m[1][2] * p.y + m[2][2] * p.z + m[3][2]});
    }
    std::optional<Bounds3> bounds() const override {
        const std::optional<Bounds3> b = surface_->bounds();
        if (!b) return std::nullopt;
        Bounds3 box;
        for (int corner = 0; corner < 8; ++corner) {
            const glm::dvec4 p((corner & 1) ? b->max.x : b->min.x, (corner & 2) ? b->max.y : b->min.y,
                               (corner & 4) ? b->max.z : b->min.z, 1.0);
            const glm::dvec4 w = placement_ * p;
            // Grow by a float ulp or so: the box is rounded to float.
            const Vec3 wf(w);
            box.expand(wf - 1e-6f * (glm::abs(wf) + 1e-30f));
            box.expand(wf + 1e-6f * (glm::abs(wf) + 1e-30f));
        }
        return box;
    }
    std::string describe() const override { return "placed " + surface_->describe(); }

private:
    ImplicitSurfacePtr surface_;
    glm::dmat4 placement_, inverse_;
};

}  // namespace

ImplicitSurfacePtr makeTransformed(ImplicitSurfacePtr surface, const Mat4& placement) {
    const glm::dmat4 m(placement);
    const double det = glm::determinant(glm::dmat3(m));
    if (!std::isfinite(det) || det == 0.0) fail("the transform is singular or not finite");
    return std::make_shared<Transformed>(std::move(surface), m);
}

ImplicitSurfacePtr makeCsg(CsgOperation op, std::vector<ImplicitSurfacePtr> operands,
                           double blend) {
    if (operands.size() < 2) fail("a CSG operation needs at least two operands");
    if (op == CsgOperation::SmoothUnion && !(std::isfinite(blend) && blend > 0.0))
        fail("parameter 'blend' must be a finite number > 0 (got ", blend, ")");
    return std::make_shared<Csg>(op, std::move(operands), blend);
}

}  // namespace strahl
