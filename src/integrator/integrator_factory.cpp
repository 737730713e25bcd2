#include <array>

#include "debug_integrators.h"
#include "ao_integrator.h"
#include "direct_integrator.h"
#include "path_integrator.h"
#include "strahl/core/error.h"

namespace strahl {

namespace {
constexpr std::array<std::string_view, 7> kNames = {"eyelight", "normal", "depth", "primid",
                                                    "direct",   "ao",     "path"};
}

std::span<const std::string_view> integratorNames() { return kNames; }

void requireIntegratorName(std::string_view name) {
    for (std::string_view n : kNames)
        if (n == name) return;
    std::string valid;
    for (std::string_view n : kNames) valid += (valid.empty() ? "" : ", ") + std::string(n);
    fail("unknown integrator '", name, "' (valid: ", valid, ")");
}

std::unique_ptr<Integrator> makeIntegrator(std::string_view name, const World& world,
                                           const IntegratorOptions& options) {
    if (options.maxDepth < 0) fail("max depth must be at least 0, got ", options.maxDepth);
    requireIntegratorName(name);
    if (name == "eyelight") return std::make_unique<EyelightIntegrator>();
    if (name == "normal") return std::make_unique<NormalIntegrator>();
    if (name == "depth") return std::make_unique<DepthIntegrator>(world);
    if (name == "primid") return std::make_unique<PrimIdIntegrator>();
    if (name == "ao") return std::make_unique<AoIntegrator>(world, options);
    if (name == "path") return std::make_unique<PathIntegrator>(options);
    return std::make_unique<DirectIntegrator>(options.hideEmitters);
}

}  // namespace strahl
