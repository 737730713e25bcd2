#pragma once
// Shared by the film tests: every AOV kind a film can carry.

#include <vector>

#include "strahl/film/film.h"

namespace strahl::test {

inline const std::vector<AovKind> kAllAovs{AovKind::Normal,   AovKind::Depth,    AovKind::Albedo,
                                           AovKind::Position, AovKind::ObjectId, AovKind::Variance};

}  // namespace strahl::test
