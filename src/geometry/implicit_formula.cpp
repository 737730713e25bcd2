#include "strahl/geometry/implicit_formula.h"

#include <utility>

#include "strahl/geometry/formula.h"

namespace strahl {

namespace {

class FormulaSurface final : public ImplicitSurfaceOf<FormulaSurface> {
public:
    explicit FormulaSurface(Formula formula) : formula_(std::move(formula)) {}

    template <class T>
    T eval(const Point3<T>& p) const {
        const T vars[3] = {p.x, p.y, p.z};
        return formula_.evaluate<T>(vars);
    }
    std::optional<Bounds3> bounds() const override { return std::nullopt; }
    std::string describe() const override { return "formula \"" + formula_.text() + "\""; }

private:
    Formula formula_;
};

}  // namespace

ImplicitSurfacePtr makeFormulaSurface(const std::string& text,
                                      const std::map<std::string, double>& parameters) {
    static const std::string kVariables[] = {"x", "y", "z"};
    return std::make_shared<FormulaSurface>(Formula::compile(text, kVariables, parameters));
}

}  // namespace strahl
