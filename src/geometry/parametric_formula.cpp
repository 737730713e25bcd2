#include "strahl/geometry/parametric_formula.h"

#include <cmath>
#include <utility>

#include "strahl/core/error.h"
#include "strahl/geometry/formula.h"

namespace strahl {

namespace {

class FormulaPatch final : public ParametricSurfaceOf<FormulaPatch> {
public:
    FormulaPatch(Formula x, Formula y, Formula z, const ParamDomain& domain)
        : x_(std::move(x)), y_(std::move(y)), z_(std::move(z)), domain_(domain) {}

    template <class T>
    Point3<T> eval(uint32_t, const T& u, const T& v) const {
        const T vars[2] = {u, v};
        return {x_.evaluate<T>(vars), y_.evaluate<T>(vars), z_.evaluate<T>(vars)};
    }
    const ParamDomain& domain() const override { return domain_; }
    std::string describe() const override {
        return concat("formula (\"", x_.text(), "\", \"", y_.text(), "\", \"", z_.text(), "\")");
    }

private:
    Formula x_, y_, z_;
    ParamDomain domain_;
};

Formula compileCoordinate(const char* name, const std::string& text,
                          const std::map<std::string, double>& parameters) {
    static const std::string kVariables[] = {"u", "v"};
    try {
        return Formula::compile(text, kVariables, parameters);
    } catch (const Error& e) {
        fail(name, ": ", e.what());
    }
}

}  // namespace

ParametricSurfacePtr makeParametricFormula(const ParametricFormulaText& text,
                                           const ParamDomain& domain,
                                           const std::map<std::string, double>& parameters) {
    auto surface = std::make_shared<FormulaPatch>(compileCoordinate("x", text.x, parameters),
                                                  compileCoordinate("y", text.y, parameters),
                                                  compileCoordinate("z", text.z, parameters), domain);
    validateParametricSurface(*surface);
    return surface;
}

}  // namespace strahl
