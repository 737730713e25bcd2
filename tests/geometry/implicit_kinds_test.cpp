// The closed family of built-in implicit surfaces (strahl/geometry/implicit_kinds.h):
// every scene-file name is answered by exactly one kind, in the documented
// order, and nothing else is.

#include "strahl/geometry/implicit_kinds.h"

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

namespace strahl {
namespace {

TEST(ImplicitKinds, NamesInTheDocumentedOrderEachAnsweredByOneKind) {
    std::vector<std::string> names;
    for (const ImplicitKind* kind : implicitKinds()) {
        ASSERT_NE(kind, nullptr);
        ASSERT_NE(kind->parse, nullptr);
        ASSERT_FALSE(kind->names.empty());
        for (std::string_view name : kind->names) {
            names.emplace_back(name);
            EXPECT_EQ(findImplicitKind(name), kind) << name;
        }
    }
    const std::vector<std::string> expected = {"sphere",    "quadric",   "torus",
                                               "superellipsoid", "blobs", "gyroid",
                                               "schwarz_p", "schwarz_d", "neovius"};
    EXPECT_EQ(names, expected);
    EXPECT_EQ(std::set<std::string>(names.begin(), names.end()).size(), names.size());
    for (const char* other : {"formula", "union", "smooth_union", "box", ""})
        EXPECT_EQ(findImplicitKind(other), nullptr) << other;
}

}  // namespace
}  // namespace strahl
