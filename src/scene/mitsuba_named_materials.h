#pragma once
// Internal to the scene module: the materials Mitsuba 3 knows by name — the
// indices of refraction of its dielectric plugins ("bk7", "air", ...) and the
// complex indices of its conductors ("Al", "Au", ...) as its RGB variants see
// them. Sources and the conversion are in the .cpp and docs/mitsuba.md.

#include <optional>
#include <span>
#include <string>
#include <string_view>

#include <glm/vec3.hpp>

namespace strahl::scene_detail::mitsuba {

// Mitsuba's named index of refraction (case-insensitive), or none.
std::optional<double> namedIor(std::string_view name);
// The names namedIor knows, for messages.
std::string namedIorList();

struct NamedConductor {
    std::string_view name;
    glm::dvec3 eta, k;  // linear sRGB
};
// Mitsuba's named conductor (exact spelling, as Mitsuba matches it), or none;
// "none" is the lossless mirror eta 0, k 1.
std::optional<NamedConductor> namedConductor(std::string_view name);
std::span<const NamedConductor> namedConductors();

}  // namespace strahl::scene_detail::mitsuba
