// The closed family of built-in parametric surfaces
// (strahl/geometry/parametric_kinds.h): every scene-file name is answered by
// exactly one kind, in the documented order, and nothing else is.

#include "strahl/geometry/parametric_kinds.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace strahl {
namespace {

TEST(ParametricKinds, NamesInTheDocumentedOrderEachAnsweredByOneKind) {
    std::vector<std::string> names;
    for (const ParametricKind* kind : parametricKinds()) {
        ASSERT_NE(kind, nullptr);
        ASSERT_NE(kind->parse, nullptr);
        for (std::string_view name : kind->names) {
            names.emplace_back(name);
            EXPECT_EQ(findParametricKind(name), kind) << name;
        }
    }
    EXPECT_EQ(names, (std::vector<std::string>{"sphere", "torus", "cylinder", "cone", "mobius"}));
    for (const char* other : {"revolution", "bezier", "heightfield", "formula", ""})
        EXPECT_EQ(findParametricKind(other), nullptr) << other;
}

}  // namespace
}  // namespace strahl
