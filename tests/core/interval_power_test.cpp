// num::powr, the real power x^y of formulas for x >= 0: a negative zero base
// is a zero base (pow(-0.0, y) alone gives -0.0 or -inf for odd integer y),
// in double and in interval arithmetic.

#include <gtest/gtest.h>

#include <cmath>

#include "strahl/core/interval.h"

namespace strahl {
namespace {

using num::Interval;

TEST(IntervalPower, NegativeZeroBaseIsZero) {
    EXPECT_EQ(num::powr(-0.0, -1.0), INFINITY);  // pow(-0.0, -1) would be -inf
    EXPECT_FALSE(std::signbit(num::powr(-0.0, 3.0)));
    EXPECT_EQ(num::powr(-0.0, 0.0), 1.0);
    EXPECT_EQ(num::powr(-2.0, 0.5), 0.0);  // clamped to 0
}

TEST(IntervalPower, IntervalWithANegativeZeroEndContainsEveryValue) {
    // x in [-0, -0], y in [-1, 1]: x^y takes 0 (y > 0), 1 (y = 0) and +inf (y < 0).
    const Interval r = num::powr(Interval(-0.0, -0.0), Interval(-1.0, 1.0));
    EXPECT_LE(r.lo, 0.0);
    EXPECT_GE(r.hi, 1.0);
    EXPECT_EQ(r.hi, INFINITY);
    const Interval one = num::powr(Interval(-0.0, 2.0), Interval(0.0, 0.0));
    EXPECT_LE(one.lo, 1.0);
    EXPECT_GE(one.hi, 1.0);
}

}  // namespace
}  // namespace strahl
