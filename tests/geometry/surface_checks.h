#pragma once
// Small checks shared by the parametric-surface tests: vectors equal to a
// tolerance, and an interval box's axis by index.

#include <gtest/gtest.h>

#include <string>

#include "strahl/core/interval.h"
#include "strahl/core/point3.h"

namespace strahl::test {

inline void expectNear(const DVec3& a, const DVec3& b, double tolerance, const std::string& what) {
    EXPECT_NEAR(a.x, b.x, tolerance) << what;
    EXPECT_NEAR(a.y, b.y, tolerance) << what;
    EXPECT_NEAR(a.z, b.z, tolerance) << what;
}

inline num::Interval axis(const Point3<num::Interval>& p, int a) {
    return a == 0 ? p.x : (a == 1 ? p.y : p.z);
}

}  // namespace strahl::test
