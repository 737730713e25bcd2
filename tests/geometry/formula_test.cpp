#include "strahl/geometry/formula.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "strahl/core/dual.h"
#include "strahl/core/interval.h"
#include "test_support.h"

namespace strahl {
namespace {

using num::Gradient3;
using num::Interval;
using num::RayDual;
using Parameters = std::map<std::string, double>;

const std::vector<std::string> kXyz = {"x", "y", "z"};
const Parameters kTorusParameters = {{"R", 1.0}, {"r", 0.25}};
constexpr const char* kTorus = "(x^2 + y^2 + z^2 + R^2 - r^2)^2 - 4*R^2*(x^2 + y^2)";
constexpr const char* kGyroid = "sin(x)*cos(y) + sin(y)*cos(z) + sin(z)*cos(x)";
constexpr const char* kSphere = "sqrt(x^2 + y^2 + z^2) - 1";
// The torus as bench/implicit_surfaces.cpp writes it (R = 1, r = 0.3).
constexpr const char* kFactoredTorus =
    "((sqrt(x^2 + y^2) - 1)^2 + (z^2 - 0.09)) * ((sqrt(x^2 + y^2) + 1)^2 + (z^2 - 0.09))";

Formula compile(std::string_view text, const Parameters& parameters = {}) {
    return Formula::compile(text, kXyz, parameters);
}

double evaluate(const Formula& f, double x, double y = 0.0, double z = 0.0) {
    const double vars[3] = {x, y, z};
    return f.evaluate(vars);
}

double evaluate(std::string_view text, double x, double y = 0.0, double z = 0.0) {
    return evaluate(compile(text), x, y, z);
}

std::string compileError(std::string_view text, const Parameters& parameters = {}) {
    return test::errorMessage([&] { (void)compile(text, parameters); });
}

std::string repeat(std::string_view part, int count) {
    std::string s;
    for (int i = 0; i < count; ++i) s += part;
    return s;
}

// ---- syntax and semantics in double -----------------------------------------------

TEST(Formula, ReadsNumbersInEveryForm) {
    EXPECT_EQ(evaluate("1", 0), 1.0);
    EXPECT_EQ(evaluate("1.5", 0), 1.5);
    EXPECT_EQ(evaluate(".5", 0), 0.5);
    EXPECT_EQ(evaluate("2.", 0), 2.0);
    EXPECT_EQ(evaluate("1e-3", 0), 1e-3);
    EXPECT_EQ(evaluate("2.5E+2", 0), 250.0);
    EXPECT_EQ(evaluate("3e2", 0), 300.0);
    EXPECT_EQ(evaluate("0.000125", 0), 0.000125);
}

TEST(Formula, FollowsPrecedenceAndAssociativity) {
    struct Case {
        const char* text;
        double expected;
    };
    // x = 2, y = 3, z = 5
    const Case cases[] = {
        // clang-format off
        {"1 + 2 * 3", 7.0},        {"(1 + 2) * 3", 9.0},     {"2 * 3 ^ 2", 18.0},
        {"-x^2", -4.0},            {"(-x)^2", 4.0},          {"-2^2", -4.0},
        {"2^3^2", 512.0},          {"(2^3)^2", 64.0},        {"x^y^0", 2.0},
        {"8 - 3 - 2", 3.0},        {"8 / 4 / 2", 1.0},       {"x - y + z", 4.0},
        {"z / x * y", 7.5},        {"2^-1", 0.5},            {"2^-x^2", 1.0 / 16.0},
        {"x * -y", -6.0},          {"x - -y", 5.0},          {"x + -y", -1.0},
        {"+x", 2.0},               {"--x", 2.0},             {"- - -x", -2.0},
        {"-x * y", -6.0},          {"x^2 * y", 12.0},        {"2^x * 3", 12.0},
        {"-(x + y) * z", -25.0},   {"z - x * y / 2", 2.0},   {"x^y / 2", 4.0},
        {"((((x))))", 2.0},        {"1 - x^2 - y", -6.0},    {"z / (x + 3)", 1.0},
        // clang-format on
    };
    for (const Case& c : cases)
        EXPECT_DOUBLE_EQ(evaluate(c.text, 2.0, 3.0, 5.0), c.expected) << c.text;
}

TEST(Formula, AllowsWhitespaceBetweenTokens) {
    EXPECT_EQ(evaluate(" \t x\n+ 1\r\n ", 2.0), 3.0);
    EXPECT_EQ(evaluate("sin ( x ) * 2", 0.0), 0.0);
    EXPECT_EQ(evaluate("min( x ,y , z )", 4.0, 3.0, 5.0), 3.0);
}

TEST(Formula, FunctionsOfOneArgumentMatchCmath) {
    struct Case {
        const char* text;
        double (*reference)(double);
        bool positiveOnly;
    };
    const Case cases[] = {
        {"sqrt(x)", [](double x) { return std::sqrt(x); }, true},
        {"log(x)", [](double x) { return std::log(x); }, true},
        {"x^0.5", [](double x) { return std::pow(x, 0.5); }, true},
        {"pow(x, 1.7)", [](double x) { return std::pow(x, 1.7); }, true},
        {"abs(x)", [](double x) { return std::abs(x); }, false},
        {"sin(x)", [](double x) { return std::sin(x); }, false},
        {"cos(x)", [](double x) { return std::cos(x); }, false},
        {"tan(x)", [](double x) { return std::tan(x); }, false},
        {"atan(x)", [](double x) { return std::atan(x); }, false},
        {"exp(x)", [](double x) { return std::exp(x); }, false},
        {"sqr(x)", [](double x) { return x * x; }, false},
        {"x^3", [](double x) { return std::pow(x, 3.0); }, false},
        {"x^-2", [](double x) { return std::pow(x, -2.0); }, false},
        {"pow(x, 5)", [](double x) { return std::pow(x, 5.0); }, false},
        {"2^x", [](double x) { return std::pow(2.0, x); }, false},
        {"e^x", [](double x) { return std::exp(x); }, false},
        {"min(x, 0.5)", [](double x) { return std::min(x, 0.5); }, false},
        {"max(x, 0.5)", [](double x) { return std::max(x, 0.5); }, false},
        {"1 / x", [](double x) { return 1.0 / x; }, false},
        {"3 - x", [](double x) { return 3.0 - x; }, false},
    };
    const double points[] = {-3.7, -1.0, -0.25, 0.1, 0.5, 1.0, 2.25, 9.5};
    for (const Case& c : cases) {
        const Formula f = compile(c.text);
        for (double x : points) {
            if (c.positiveOnly && x <= 0.0) continue;
            EXPECT_DOUBLE_EQ(evaluate(f, x), c.reference(x)) << c.text << " at x = " << x;
        }
    }
}

TEST(Formula, FunctionsOfSeveralArgumentsMatchCmath) {
    const Formula minimum = compile("min(x, y, z)"), maximum = compile("max(x, y, z, 0.5)");
    const Formula power = compile("pow(x, y)"), ratio = compile("atan(y / x)");
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-4.0, 4.0);
    for (int i = 0; i < 200; ++i) {
        const double x = u(rng), y = u(rng), z = u(rng);
        EXPECT_EQ(evaluate(minimum, x, y, z), std::min({x, y, z}));
        EXPECT_EQ(evaluate(maximum, x, y, z), std::max({x, y, z, 0.5}));
        EXPECT_DOUBLE_EQ(evaluate(power, std::abs(x), y), std::pow(std::abs(x), y));
        EXPECT_DOUBLE_EQ(evaluate(ratio, x, y), std::atan(y / x));
    }
}

TEST(Formula, PowersWithIntegerExponentsAcceptNegativeBases) {
    EXPECT_DOUBLE_EQ(evaluate("x^3", -2.0), -8.0);
    EXPECT_DOUBLE_EQ(evaluate("x^(1 + 2)", -2.0), -8.0);  // folded to an integer
    EXPECT_DOUBLE_EQ(evaluate("pow(x, 4)", -2.0), 16.0);
    EXPECT_DOUBLE_EQ(evaluate("x^-3", -2.0), -0.125);
    EXPECT_DOUBLE_EQ(evaluate("(-2)^3 + x", 0.0), -8.0);
    EXPECT_DOUBLE_EQ(compile("x^n", {{"n", 3.0}}).evaluate(std::array{-2.0, 0.0, 0.0}.data()),
                     -8.0);
}

TEST(Formula, RealPowersClampNegativeBasesToZero) {
    EXPECT_EQ(evaluate("x^2.5", -2.0), 0.0);
    EXPECT_EQ(evaluate("pow(x, 0.5)", -4.0), 0.0);
    EXPECT_EQ(evaluate("pow(x, y)", -2.0, 3.0), 0.0);  // y is not a compile-time constant
    EXPECT_EQ(evaluate("(-8)^(1/3) + x", 0.0), 0.0);
    EXPECT_DOUBLE_EQ(evaluate("x^2.5", 4.0), 32.0);
}

TEST(Formula, OutOfDomainFunctionsFollowTheNumLibrary) {
    EXPECT_EQ(evaluate("sqrt(x)", -1.0), 0.0);
    EXPECT_EQ(evaluate("log(x)", 0.0), -std::numeric_limits<double>::infinity());
    EXPECT_EQ(evaluate("log(x)", -1.0), -std::numeric_limits<double>::infinity());
}

TEST(Formula, KnowsConstantsAndParameters) {
    EXPECT_DOUBLE_EQ(evaluate("pi + x", 0.0), 3.14159265358979323846);
    EXPECT_DOUBLE_EQ(evaluate("e + x", 0.0), 2.71828182845904523536);
    const Formula torus = compile(kTorus, kTorusParameters);
    const double x = 0.3, y = -0.8, z = 0.1, R = 1.0, r = 0.25;
    const double s = x * x + y * y + z * z + R * R - r * r;
    EXPECT_DOUBLE_EQ(evaluate(torus, x, y, z), s * s - 4.0 * R * R * (x * x + y * y));
    EXPECT_NEAR(evaluate(torus, 1.25, 0.0, 0.0), 0.0, 1e-12);  // on the outer equator
    EXPECT_NEAR(evaluate(torus, 0.0, 1.0, 0.25), 0.0, 1e-12);  // on the top circle
}

TEST(Formula, NamesAreCaseSensitiveWithUnderscoresAndDigits) {
    const Parameters p = {{"R", 2.0}, {"r", 0.5}, {"radius_2", 7.0}, {"_k", 3.0}};
    EXPECT_EQ(compile("R - r + radius_2 * _k + x", p).evaluate(std::array{1.0, 0.0, 0.0}.data()),
              23.5);
}

TEST(Formula, TakesAnyVariableNames) {
    const std::vector<std::string> uv = {"u", "v"};
    const Formula f = Formula::compile("cos(u) * (2 + v)", uv);
    EXPECT_EQ(f.variableCount(), 2u);
    EXPECT_DOUBLE_EQ(f.evaluate(std::array{0.5, 1.5}.data()), std::cos(0.5) * 3.5);
    EXPECT_EQ(f.text(), "cos(u) * (2 + v)");
    const Formula constant = Formula::compile("42", {});
    EXPECT_EQ(constant.variableCount(), 0u);
    EXPECT_EQ(constant.evaluate<double>(nullptr), 42.0);
}

TEST(Formula, CopiesEvaluateLikeTheOriginal) {
    const Formula original = compile(kGyroid);
    const Formula copy = original;  // NOLINT: testing the copy
    Formula moved = compile("x");
    moved = compile(kGyroid);
    EXPECT_EQ(evaluate(copy, 0.3, 0.7, -1.1), evaluate(original, 0.3, 0.7, -1.1));
    EXPECT_EQ(evaluate(moved, 0.3, 0.7, -1.1), evaluate(original, 0.3, 0.7, -1.1));
}

// The examples of docs/formulas.md, each at a point of its surface.
TEST(Formula, DocumentedExamplesVanishOnTheirSurfaces) {
    struct Case {
        const char* text;
        Parameters parameters;
        std::array<double, 3> point;
        double value;
    };
    const Case cases[] = {
        {"x^2 + y^2 + z^2 - 1", {}, {0, 0, 1}, 0.0},
        {kTorus, kTorusParameters, {0, 1.25, 0}, 0.0},
        {kGyroid, {}, {0, 0, 0}, 0.0},
        {"abs(sin(k*x)*cos(k*y) + sin(k*y)*cos(k*z) + sin(k*z)*cos(k*x)) - t",
         {{"k", 6.283}, {"t", 0.3}},
         {0, 0, 0},
         -0.3},
        {"x^4 - 5*x^2 + y^4 - 5*y^2 + z^4 - 5*z^2 + 11.8", {}, {0, 0, 0}, 11.8},
        {"(x^2 + 9/4*y^2 + z^2 - 1)^3 - x^2*z^3 - 9/80*y^2*z^3", {}, {1, 0, 0}, 0.0},
        {"(x^8 + y^8 + z^8)^(1/8) - 1", {}, {0, -1, 0}, 0.0},
        {"max(abs(x) - a, abs(y) - b, abs(z) - c)",
         {{"a", 1}, {"b", 0.5}, {"c", 0.25}},
         {0.2, -0.5, 0.1},
         0.0},
        {"min(x^2 + y^2 + z^2 - 1, (x - 1.2)^2 + y^2 + z^2 - 0.5)", {}, {-1, 0, 0}, 0.0},
        {"x^2 + y^2 - z", {}, {0.6, 0.8, 1.0}, 0.0},
    };
    for (const Case& c : cases) {
        const Formula f = compile(c.text, c.parameters);
        EXPECT_NEAR(f.evaluate(c.point.data()), c.value, 1e-12) << c.text;
    }
}

// ---- errors ---------------------------------------------------------------------

TEST(FormulaErrors, PointAtTheOffendingColumn) {
    struct Case {
        const char* text;
        const char* message;
    };
    const Case cases[] = {
        {"", "column 1: empty formula"},
        {"   ", "column 1: empty formula"},
        {"x^2 +",
         "column 6: expected an operand (a number, a name or '('), found the end of "
         "the formula"},
        {"x ** 2", "column 4: expected an operand (a number, a name or '('), found '*'"},
        {"()", "column 2: expected an operand (a number, a name or '('), found ')'"},
        {"x + / y", "column 5: expected an operand (a number, a name or '('), found '/'"},
        {"(x + 1",
         "column 7: expected ')' to close the '(' at column 1, found the end of the "
         "formula"},
        {"2 * (x + (y - 1)",
         "column 17: expected ')' to close the '(' at column 5, found the "
         "end of the formula"},
        {"x + 1)", "column 6: unmatched ')'"},
        {"(x, y)", "column 3: expected ')' to close the '(' at column 1, found ','"},
        {"x, y", "column 2: expected an operator or the end of the formula, found ','"},
        {"2x", "column 2: expected an operator, found 'x' (a product needs an explicit '*')"},
        {"x y", "column 3: expected an operator, found 'y' (a product needs an explicit '*')"},
        {"2 (x)", "column 3: expected an operator, found '(' (a product needs an explicit '*')"},
        {"(x + 1) 3",
         "column 9: expected an operator, found '3' (a product needs an explicit "
         "'*')"},
        {"x # y", "column 3: unexpected character '#'"},
        {"x*π", "column 3: unexpected character 'π'"},
        {"x^2 = 1",
         "column 5: unexpected character '=': write the expression only (a - b "
         "rather than a = b)"},
        {"1e", "column 1: malformed number '1e': the exponent needs digits"},
        {"x + 2.5e+", "column 5: malformed number '2.5e+': the exponent needs digits"},
        {"1.2.3", "column 1: malformed number '1.2.3'"},
        {"x + .", "column 5: malformed number '.'"},
        {"1e999 * x", "column 1: number '1e999' is out of the range of double"},
        {"sin(x",
         "column 6: expected ',' or ')' to close the '(' of sin at column 4, found the "
         "end of the formula"},
        {"sin()", "column 1: sin takes 1 argument, got 0"},
        {"sin(x, y)", "column 1: sin takes 1 argument, got 2"},
        {"1 + pow(x)", "column 5: pow takes 2 arguments, got 1"},
        {"min(x)", "column 1: min takes at least 2 arguments, got 1"},
        {"max(x,)", "column 7: expected an operand (a number, a name or '('), found ')'"},
        {"sin x", "column 1: 'sin' is a function: call it as sin(...)"},
        {"2 * x(y)",
         "column 5: 'x' is a variable, not a function (a product needs an explicit "
         "'*')"},
        {"pi(2)",
         "column 1: 'pi' is a constant, not a function (a product needs an explicit "
         "'*')"},
        {"x / 0", "column 5: division by zero ('0' is 0)"},
        {"x / (pi - pi)", "column 5: division by zero ('(pi - pi)' is 0)"},
        {"log(0)", "column 1: 'log(0)' evaluates to -inf (a constant must be finite)"},
        {"x + exp(1000)", "column 5: 'exp(1000)' evaluates to inf (a constant must be finite)"},
        {"0^-1 * y", "column 1: '0^-1' evaluates to inf (a constant must be finite)"},
        {"x +\n  * 2", "column 7: expected an operand (a number, a name or '('), found '*'"},
    };
    for (const Case& c : cases) EXPECT_EQ(compileError(c.text), c.message) << c.text;
}

TEST(FormulaErrors, UnknownNamesListTheKnownOnes) {
    const std::string message = compileError("x + radius", kTorusParameters);
    EXPECT_EQ(message,
              "column 5: unknown name 'radius'; variables: x, y, z; parameters: R, r; "
              "constants: e, pi; functions: abs, atan, cos, exp, log, max, min, pow, sin, sqr, "
              "sqrt, tan");
    EXPECT_TRUE(test::contains(compileError("foo(x)"),
                               "column 1: unknown function 'foo'; "
                               "variables: x, y, z; parameters: none;"));
}

TEST(FormulaErrors, SuggestTheNameWithTheRightCase) {
    EXPECT_TRUE(test::contains(compileError("Sin(x)"),
                               "column 1: unknown function 'Sin' (did you mean 'sin'?);"));
    EXPECT_TRUE(test::contains(compileError("2*PI*x"),
                               "column 3: unknown name 'PI' (did you mean 'pi'?);"));
    EXPECT_TRUE(
        test::contains(compileError("X + y"), "column 1: unknown name 'X' (did you mean 'x'?);"));
}

TEST(FormulaErrors, RejectBadParameters) {
    EXPECT_EQ(compileError("x", {{"x", 1.0}}), "parameter 'x' shadows the variable 'x'");
    EXPECT_EQ(compileError("x", {{"pi", 3.0}}), "parameter 'pi' shadows the constant 'pi'");
    EXPECT_EQ(compileError("x", {{"sin", 1.0}}), "parameter 'sin' shadows the function 'sin'");
    EXPECT_EQ(compileError("x", {{"R", std::numeric_limits<double>::infinity()}}),
              "parameter 'R' is not finite (inf)");
    EXPECT_EQ(compileError("x", {{"R", std::nan("")}}), "parameter 'R' is not finite (nan)");
    EXPECT_TRUE(
        test::contains(compileError("x", {{"2R", 1.0}}), "parameter '2R' is not a valid name"));
    EXPECT_TRUE(test::contains(compileError("x", {{"", 1.0}}), "parameter '' is not a valid name"));
}

TEST(FormulaErrors, RejectBadVariableLists) {
    const std::vector<std::string> twice = {"x", "x"}, function = {"x", "exp"}, bad = {"x y"};
    EXPECT_EQ(test::errorMessage([&] { (void)Formula::compile("x", twice); }),
              "variable 'x' is listed twice");
    EXPECT_EQ(test::errorMessage([&] { (void)Formula::compile("x", function); }),
              "variable 'exp' has the name of a function");
    EXPECT_EQ(test::errorMessage([&] { (void)Formula::compile("1", bad); }),
              "variable 'x y' is not a valid name");
}

TEST(FormulaErrors, RejectFormulasTooDeeplyNestedToParse) {
    EXPECT_NO_THROW(compile(repeat("(", 90) + "x" + repeat(")", 90)));
    EXPECT_EQ(compileError(repeat("(", 150) + "x" + repeat(")", 150)),
              "column 101: formula is too deeply nested (more than 100 levels of parentheses, "
              "calls, signs or exponents)");
    EXPECT_TRUE(test::contains(compileError(repeat("-", 5000) + "x"),
                               "column 101: formula is too deeply nested"));
    EXPECT_TRUE(test::contains(compileError(repeat("sin(", 200) + "x" + repeat(")", 200)),
                               "formula is too deeply nested"));
}

TEST(FormulaErrors, RejectFormulasTooLargeForTheEvaluator) {
    // A chain of 1200 additions is deeper than the tape builder recurses.
    EXPECT_EQ(compileError("x" + repeat(" + y", 1200)),
              "column 1: formula is too deeply nested for the evaluator (a chain of more than "
              "1000 operations)");
    // 70 values computed in the first half and all used again in the second
    // half are live at once: more than 64 registers.
    std::string sum, product;
    for (int i = 1; i <= 70; ++i) {
        const std::string term = "sin(x + " + std::to_string(i) + ")";
        sum += (i > 1 ? " + " : "") + term;
        product += (i > 1 ? " * " : "") + term;
    }
    EXPECT_TRUE(test::contains(compileError(sum + " + " + product),
                               "formula is too large for the evaluator (it needs more than 64 "
                               "registers)"));
}

// ---- the tape ---------------------------------------------------------------------

TEST(FormulaTape, FoldsConstantsIntoImmediates) {
    struct Case {
        const char* text;
        size_t instructions;
        double valueAtTwo;
    };
    const double pi = 3.14159265358979323846;
    const Case cases[] = {
        {"2*pi*x", 1, 4 * pi},
        {"x*2*pi", 1, 4 * pi},
        {"x * sqrt(2) / 2", 1, std::sqrt(2.0)},
        {"x / 2 / 4", 1, 0.25},
        {"sin(pi/6) * x", 1, 1.0},
        {"x - (1 + 2)", 1, -1.0},
        {"x + 1 - 3", 1, 0.0},
        {"1 - (x + 2)", 1, -3.0},
        {"3 - (1 - x)", 1, 4.0},
        {"-(x + 1)", 1, -3.0},
        {"1 / x", 1, 0.5},
        {"x^-1", 1, 0.5},
        {"2^x", 1, 4.0},
        {"x^2.5", 1, std::pow(2.0, 2.5)},
        {"x^3", 1, 8.0},
        {"min(x, 1, 2, y, 3)", 2, -1.0},
        {"max(x, 1, 2, y, 3)", 2, 3.0},
        {"-(x * 3) / 4", 1, -1.5},
    };
    for (const Case& c : cases) {
        const Formula f = compile(c.text);
        EXPECT_EQ(f.instructionCount(), c.instructions) << c.text;
        EXPECT_DOUBLE_EQ(evaluate(f, 2.0, -1.0), c.valueAtTwo) << c.text;
    }
    EXPECT_EQ(compile("(R^2 - r^2) + x", kTorusParameters).instructionCount(), 1u);
}

TEST(FormulaTape, DropsOperationsThatChangeNothing) {
    for (const char* text :
         {"x", "+x", "--x", "-(-x)", "x + 0", "0 + x", "x - 0", "x * 1", "1 * x", "x / 1", "x^1",
          "(x)", "max(x, x)", "x + 1 - 1", "x * 2 / 2", "2 - (2 - x)"}) {
        const Formula f = compile(text);
        EXPECT_EQ(f.instructionCount(), 0u) << text;
        EXPECT_EQ(evaluate(f, -1.5), -1.5) << text;
    }
    EXPECT_EQ(compile("0 - x").instructionCount(), 1u);
    EXPECT_EQ(compile("x * -1").instructionCount(), 1u);
}

TEST(FormulaTape, FusesProductsAndSquaresIntoAdditions) {
    struct Case {
        const char* text;
        size_t instructions;
    };
    const Case cases[] = {
        {"x*y + z", 1},
        {"z + x*y", 1},
        {"2*x + y", 1},
        {"x - 3*y", 1},
        {"x^2 + y", 1},
        {"x^2 + y^2", 1},
        {"x^2 + y^2 + z^2", 2},
        {"x*y + y*z + z*x", 3},
        {"x*y - z", 2},
        {"sqrt(x^2 + y^2)", 1},
        {"z + (y - 0.5)^2", 1},
        {"x^2 - 0.25", 1},
        // hypot, z^2 - r^2, two (t + (h -+ R)^2), the product
        {kFactoredTorus, 5},
    };
    std::mt19937_64 rng(10);
    std::uniform_real_distribution<double> u(-3.0, 3.0);
    for (const Case& c : cases) {
        const Formula f = compile(c.text);
        EXPECT_EQ(f.instructionCount(), c.instructions) << c.text;
    }
    // The fused instructions do the same arithmetic as the separate ones.
    for (int i = 0; i < 100; ++i) {
        const double x = u(rng), y = u(rng), z = u(rng);
        EXPECT_EQ(evaluate("x*y + z", x, y, z), x * y + z);
        EXPECT_EQ(evaluate("x - 3*y", x, y, z), x - 3 * y);
        EXPECT_EQ(evaluate("x^2 + y^2 + z^2", x, y, z), x * x + y * y + z * z);
        EXPECT_EQ(evaluate("sqrt(x^2 + y^2)", x, y, z), std::sqrt(x * x + y * y));
        EXPECT_EQ(evaluate("z + (y - 0.5)^2", x, y, z), z + (y - 0.5) * (y - 0.5));
        EXPECT_EQ(evaluate("x^2 - 0.25", x, y, z), x * x - 0.25);
    }
}

TEST(FormulaTape, AConstantFormulaIsOneInstruction) {
    const Formula f = compile("2 * pi - e^2");
    EXPECT_EQ(f.instructionCount(), 1u);
    EXPECT_DOUBLE_EQ(evaluate(f, 9.0), 2.0 * 3.14159265358979323846 - std::exp(2.0));
    for (size_t i = 0; i < 3; ++i) EXPECT_FALSE(f.usesVariable(i));
    const Interval box[3] = {{-1, 1}, {-1, 1}, {-1, 1}};
    EXPECT_TRUE(f.evaluate(box).contains(evaluate(f, 0.0)));
}

TEST(FormulaTape, ComputesRepeatedSubexpressionsOnce) {
    EXPECT_EQ(compile("sin(x)*sin(x) + sin(x)").instructionCount(), 2u);  // sin, s + s^2
    EXPECT_EQ(compile("(x^2 + y^2)^2 + (x^2 + y^2)").instructionCount(), 2u);
    EXPECT_EQ(compile("x*y + y*x").instructionCount(), 2u);  // mul, add
    EXPECT_EQ(compile("sin(x) + sin(x) + sin(x)").instructionCount(), 3u);
    // The torus: s = x² + y², s + z², + (R² - r²), its square, - 4R²·s.
    const Formula torus = compile(kTorus, kTorusParameters);
    EXPECT_EQ(torus.instructionCount(), 5u);
}

TEST(FormulaTape, ReusesDeadRegisters) {
    const Formula torus = compile(kTorus, kTorusParameters);
    EXPECT_LE(torus.registerCount(), 6u);
    // 400 terms in a row still need only a handful of registers.
    std::string text = "0";
    double expected = 0.0;
    for (int i = 1; i <= 400; ++i) {
        text += " + " + std::to_string(i) + "*x^" + std::to_string(i % 7);
        expected += i * std::pow(1.1, i % 7);
    }
    const Formula poly = compile(text);
    EXPECT_LE(poly.registerCount(), 10u);  // x, x^2..x^6 (shared), sum, term
    EXPECT_NEAR(evaluate(poly, 1.1), expected, 1e-9 * expected);
    // 40 values live at once fit (compare the 70 of RejectFormulasTooLargeForTheEvaluator).
    std::string sum, product;
    double expectedSum = 0.0, expectedProduct = 1.0;
    for (int i = 1; i <= 40; ++i) {
        const std::string term = "sin(x + " + std::to_string(i) + ")";
        sum += (i > 1 ? " + " : "") + term;
        product += (i > 1 ? " * " : "") + term;
        expectedSum += std::sin(0.3 + i);
        expectedProduct *= std::sin(0.3 + i);
    }
    const Formula wide = compile(sum + " + " + product);
    EXPECT_LE(wide.registerCount(), Formula::kMaxRegisters);
    EXPECT_GE(wide.registerCount(), 40u);
    EXPECT_NEAR(evaluate(wide, 0.3), expectedSum + expectedProduct, 1e-12);
}

TEST(FormulaTape, KnowsWhichVariablesAreUsed) {
    const Formula f = compile("x + z");
    EXPECT_TRUE(f.usesVariable(0));
    EXPECT_FALSE(f.usesVariable(1));
    EXPECT_TRUE(f.usesVariable(2));
    EXPECT_FALSE(f.usesVariable(3));
    EXPECT_FALSE(compile("y^0 + x").usesVariable(1));
    EXPECT_TRUE(compile("x * 0").usesVariable(0));  // no algebra beyond constants: x may be inf
    EXPECT_TRUE(compile("z").usesVariable(2));
    EXPECT_FALSE(compile("z").usesVariable(0));
}

// ---- gradients ----------------------------------------------------------------------

Gradient3 gradientAt(const Formula& f, double x, double y, double z) {
    const Gradient3 vars[3] = {Gradient3::variable(x, 0), Gradient3::variable(y, 1),
                               Gradient3::variable(z, 2)};
    return f.evaluate(vars);
}

void expectGradient(const Formula& f, double x, double y, double z, double value,
                    std::array<double, 3> gradient) {
    const Gradient3 g = gradientAt(f, x, y, z);
    const double scale = 1.0 + std::abs(value) + std::abs(gradient[0]) + std::abs(gradient[1]) +
                         std::abs(gradient[2]);
    EXPECT_NEAR(g.v, value, 1e-13 * scale) << f.text();
    for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(g.d[static_cast<size_t>(i)], gradient[static_cast<size_t>(i)], 1e-13 * scale)
            << f.text() << " d/d"
            << "xyz"[i] << " at " << x << ", " << y << ", " << z;
}

TEST(FormulaGradient, MatchesTheTorusDerivatives) {
    const Formula torus = compile(kTorus, kTorusParameters);
    const double R = 1.0, r = 0.25;
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> u(-1.5, 1.5);
    for (int i = 0; i < 100; ++i) {
        const double x = u(rng), y = u(rng), z = u(rng);
        const double s = x * x + y * y + z * z + R * R - r * r;
        expectGradient(torus, x, y, z, s * s - 4 * R * R * (x * x + y * y),
                       {4 * x * s - 8 * R * R * x, 4 * y * s - 8 * R * R * y, 4 * z * s});
    }
}

TEST(FormulaGradient, MatchesTheGyroidDerivatives) {
    const Formula gyroid = compile(kGyroid);
    std::mt19937_64 rng(2);
    std::uniform_real_distribution<double> u(-7.0, 7.0);
    for (int i = 0; i < 100; ++i) {
        const double x = u(rng), y = u(rng), z = u(rng);
        using std::cos, std::sin;
        expectGradient(gyroid, x, y, z, sin(x) * cos(y) + sin(y) * cos(z) + sin(z) * cos(x),
                       {cos(x) * cos(y) - sin(z) * sin(x), -sin(x) * sin(y) + cos(y) * cos(z),
                        -sin(y) * sin(z) + cos(z) * cos(x)});
    }
}

TEST(FormulaGradient, MatchesTheSphereDerivatives) {
    const Formula sphere = compile(kSphere);
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(-2.0, 2.0);
    for (int i = 0; i < 100; ++i) {
        const double x = u(rng), y = u(rng), z = u(rng);
        const double length = std::sqrt(x * x + y * y + z * z);
        expectGradient(sphere, x, y, z, length - 1.0, {x / length, y / length, z / length});
    }
}

// Every instruction's derivative, against central differences.
TEST(FormulaGradient, MatchesFiniteDifferencesForEveryOperation) {
    const char* formulas[] = {
        "x / y + 2 / z",
        "3 - x * y",
        "x^2.5 + 1.5^y - z^-3",
        "pow(x, y) + pow(z, 2)",
        "min(x, 0.7) + max(y, z) - min(x, y, z)",
        "atan(x) + tan(y / 3) + exp(z / 2) + log(x + 3)",
        "sqrt(x^2 + 1) * abs(y - 3) - sqr(z)",
        "x^-3 + y^5 - (x * 4) / 7",
        "sin(x) * cos(y) - x / (y * z)",
        "2 * pi * x - e^z",
        "max(x, 1.8) * min(z, 0.9)",
        "x*y + z*2 - 3*x + x^2 + y^2 - z*x",
        "sqrt(x^2 + y^2) - 1 + (z - 0.5)^2 + y^2 - 0.25",
        kFactoredTorus,
    };
    std::mt19937_64 rng(4);
    std::uniform_real_distribution<double> u(0.5, 2.0);
    for (const char* text : formulas) {
        const Formula f = compile(text);
        for (int i = 0; i < 40; ++i) {
            const std::array<double, 3> p = {u(rng), u(rng), u(rng)};
            const Gradient3 g = gradientAt(f, p[0], p[1], p[2]);
            EXPECT_DOUBLE_EQ(g.v, evaluate(f, p[0], p[1], p[2])) << text;
            for (size_t k = 0; k < 3; ++k) {
                const double h = 1e-6;
                std::array<double, 3> plus = p, minus = p;
                plus[k] += h;
                minus[k] -= h;
                const double difference =
                    (f.evaluate(plus.data()) - f.evaluate(minus.data())) / (2.0 * h);
                EXPECT_NEAR(g.d[k], difference, 1e-6 * (1.0 + std::abs(difference)))
                    << text << " d/d"
                    << "xyz"[k] << " at " << p[0] << ", " << p[1] << ", " << p[2];
            }
        }
    }
}

TEST(FormulaGradient, RealPowersAreFlatWhereTheBaseIsClamped) {
    const Gradient3 g = gradientAt(compile("pow(x, 2.5) + pow(y, z)"), -1.0, -2.0, 1.5);
    EXPECT_EQ(g.v, 0.0);
    for (double d : g.d) EXPECT_EQ(d, 0.0);
    const Gradient3 h = gradientAt(compile("pow(x, y)"), 2.0, 3.0, 0.0);
    EXPECT_DOUBLE_EQ(h.v, 8.0);
    EXPECT_DOUBLE_EQ(h.d[0], 3.0 * 4.0);            // y x^(y-1)
    EXPECT_DOUBLE_EQ(h.d[1], 8.0 * std::log(2.0));  // x^y ln x
}

// ---- intervals ------------------------------------------------------------------------

// Formulas for the enclosure properties: every function and instruction,
// including divisions by intervals around 0, logs and roots near their domain
// edges, and poles of tan.
const char* const kEnclosureFormulas[] = {
    kTorus,
    kGyroid,
    kSphere,
    "x / y + y / (z + 2)",
    "(x - y) / (x + y)",
    "1 - x / y",
    "log(x^2 + y^2 + 1e-3) * z",
    "log(abs(x)) + log(y + 3)",
    "sqrt(abs(x * y)) - z",
    "sqrt(x + 1) + sqrt(1 - y)",
    "sin(3 * x) * cos(2 * y) + tan(z / 2)",
    "tan(x) - cos(y + z)",
    "atan(x / (1 + y^2)) - atan(z)",
    "exp(-(x^2 + y^2)) - 0.5",
    "exp(x) * exp(-y) + z",
    "min(x, y, z) + max(x * y, 2, z)",
    "max(abs(x), abs(y), abs(z)) - 1",
    "x^3 - 3 * x * y^2 + z^4",
    "x^-2 + y^-3 - z^7",
    "pow(abs(x), 2.5) + pow(abs(y) + 1, z)",
    "2^x - e^y + 0.5^z",
    "pow(x, y)",
    "sqr(sin(x)) + sqr(cos(x)) - 1",
    "abs(x) - abs(y) + abs(z)",
    "x - x",
    "10 - x*y*z / 3",
    "x*y - 2*z + x^2 + (y - 1)^2",
    kFactoredTorus,
};

Interval randomInterval(std::mt19937_64& rng) {
    std::uniform_real_distribution<double> centre(-3.0, 3.0), logWidth(-6.0, 0.5);
    const double c = centre(rng), w = std::pow(10.0, logWidth(rng));
    return {c - w, c + w};
}

double pointIn(const Interval& i, std::mt19937_64& rng) {
    return std::uniform_real_distribution<double>(i.lo, i.hi)(rng);
}

TEST(FormulaInterval, EnclosesEveryPointOfTheBox) {
    std::mt19937_64 rng(5);
    for (const char* text : kEnclosureFormulas) {
        const Formula f = compile(text, kTorusParameters);
        int checked = 0;
        for (int box = 0; box < 300; ++box) {
            const Interval b[3] = {randomInterval(rng), randomInterval(rng), randomInterval(rng)};
            const Interval range = f.evaluate(b);
            ASSERT_FALSE(std::isnan(range.lo) || std::isnan(range.hi)) << text;
            ASSERT_LE(range.lo, range.hi) << text;
            for (int k = 0; k < 20; ++k) {
                const double p[3] = {pointIn(b[0], rng), pointIn(b[1], rng), pointIn(b[2], rng)};
                const double value = f.evaluate(p);
                if (std::isnan(value)) continue;  // (pow(x, y) at 0^0 etc. never happens here)
                ++checked;
                EXPECT_TRUE(range.contains(value))
                    << text << " at " << p[0] << ", " << p[1] << ", " << p[2] << ": " << value
                    << " outside [" << range.lo << ", " << range.hi << "]";
            }
        }
        EXPECT_EQ(checked, 300 * 20) << text;
    }
}

TEST(FormulaInterval, PointBoxesAreTight) {
    const Formula torus = compile(kTorus, kTorusParameters);
    const Interval p[3] = {0.3, -0.4, 0.2};
    const Interval range = torus.evaluate(p);
    const double value = evaluate(torus, 0.3, -0.4, 0.2);
    EXPECT_TRUE(range.contains(value));
    EXPECT_LT(range.width(), 1e-13);  // a few ulps per instruction
}

// The tip of docs/formulas.md: each occurrence of a variable widens the range.
TEST(FormulaInterval, FewerOccurrencesGiveTighterRanges) {
    const Interval box[3] = {{0.0, 2.0}, 0.0, 0.0};
    const Interval expanded = compile("x^2 - 2*x + 1").evaluate(box);
    const Interval square = compile("(x - 1)^2").evaluate(box);
    EXPECT_NEAR(expanded.lo, -3.0, 1e-12);
    EXPECT_NEAR(expanded.hi, 5.0, 1e-12);
    EXPECT_NEAR(square.lo, 0.0, 1e-12);
    EXPECT_NEAR(square.hi, 1.0, 1e-12);
    const Interval product = compile("x*x - x^2").evaluate(box);  // x*x is a square too
    EXPECT_NEAR(product.lo, -4.0, 1e-12);
    EXPECT_NEAR(product.hi, 4.0, 1e-12);
}

TEST(FormulaInterval, NeverProducesNaNFromInfiniteBounds) {
    const double inf = std::numeric_limits<double>::infinity();
    struct Case {
        const char* text;
        Interval x, y;
    };
    const Case cases[] = {
        {"exp(x) - exp(y)", {800, 900}, {800, 900}},  // both overflow
        {"log(x) + exp(y)", {-2, -1}, {800, 900}},    // -inf plus +inf
        {"x / y", {1, inf}, {1, inf}},                // inf / inf corner
        {"x^3 - y^3", {1e200, 1e201}, {1e200, 1e201}},
        {"sqr(x) - sqr(y)", {1e200, 1e201}, {-1e201, -1e200}},
    };
    for (const Case& c : cases) {
        const Interval box[3] = {c.x, c.y, 0.0};
        const Interval range = compile(c.text).evaluate(box);
        EXPECT_FALSE(std::isnan(range.lo)) << c.text;
        EXPECT_FALSE(std::isnan(range.hi)) << c.text;
        EXPECT_LE(range.lo, range.hi) << c.text;
    }
    const Interval box[3] = {{1, inf}, {1, inf}, 0.0};
    const Interval quotient = compile("x / y").evaluate(box);
    EXPECT_LE(quotient.lo, 0.0);
    EXPECT_EQ(quotient.hi, inf);
}

TEST(FormulaInterval, HighPowersEncloseTheExactValue) {
    std::mt19937_64 rng(6);
    std::uniform_real_distribution<double> u(0.5, 1.5);
    for (int n : {5, 17, 33, 64, 100, -40}) {
        const Formula f = compile("x^" + std::to_string(n));
        for (int i = 0; i < 500; ++i) {
            const double x = u(rng);
            const Interval point[3] = {x, 0.0, 0.0};
            const Interval range = f.evaluate(point);
            const long double exact = std::pow(static_cast<long double>(x), n);
            EXPECT_LE(static_cast<long double>(range.lo), exact) << "x^" << n << " at " << x;
            EXPECT_GE(static_cast<long double>(range.hi), exact) << "x^" << n << " at " << x;
        }
    }
}

TEST(FormulaInterval, TrigonometryOfLargeArgumentsStaysConservative) {
    std::mt19937_64 rng(8);
    const Formula f = compile("sin(x) + cos(y)");
    for (double centre : {1e9, 3e12, 7e15}) {
        for (int i = 0; i < 50; ++i) {
            const Interval b[3] = {{centre + i, centre + i + 6}, {centre + i, centre + i + 6}, 0};
            const Interval range = f.evaluate(b);
            for (int k = 0; k < 20; ++k) {
                const double p[3] = {pointIn(b[0], rng), pointIn(b[1], rng), 0.0};
                EXPECT_TRUE(range.contains(f.evaluate(p))) << centre;
            }
        }
    }
}

// ---- along a ray ----------------------------------------------------------------------

TEST(FormulaRayDual, BoundsTheValueAndTheSlopeAlongARaySegment) {
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> u(-2.0, 2.0), start(0.0, 3.0), logLength(-5.0, 0.3);
    for (const char* text : kEnclosureFormulas) {
        const Formula f = compile(text, kTorusParameters);
        int checked = 0;
        for (int segment = 0; segment < 200; ++segment) {
            const std::array<double, 3> o = {u(rng), u(rng), u(rng)}, d = {u(rng), u(rng), u(rng)};
            const double t0 = start(rng), t1 = t0 + std::pow(10.0, logLength(rng));
            const Interval t(t0, t1);
            RayDual ray[3];
            for (size_t k = 0; k < 3; ++k) {
                ray[k].v = Interval(o[k]) + t * Interval(d[k]);
                ray[k].d[0] = Interval(d[k]);
            }
            const RayDual F = f.evaluate(ray);
            for (int s = 0; s < 20; ++s) {
                const double ts = std::uniform_real_distribution<double>(t0, t1)(rng);
                num::Dual<double, 1> point[3];
                for (size_t k = 0; k < 3; ++k) {
                    point[k].v = o[k] + ts * d[k];
                    point[k].d[0] = d[k];
                }
                const num::Dual<double, 1> Ft = f.evaluate(point);
                if (std::isnan(Ft.v) || std::isnan(Ft.d[0])) continue;
                ++checked;
                EXPECT_TRUE(F.v.contains(Ft.v)) << text << " F(" << ts << ") = " << Ft.v
                                                << " outside [" << F.v.lo << ", " << F.v.hi << "]";
                EXPECT_TRUE(F.d[0].contains(Ft.d[0]))
                    << text << " F'(" << ts << ") = " << Ft.d[0] << " outside [" << F.d[0].lo
                    << ", " << F.d[0].hi << "]";
            }
        }
        // Only the slope of sqrt, log or pow exactly at a clamped point is NaN.
        EXPECT_GE(checked, 200 * 20 * 9 / 10) << text;
    }
}

TEST(FormulaRayDual, AgreesWithTheGradientAlongTheRay) {
    const Formula torus = compile(kTorus, kTorusParameters);
    const std::array<double, 3> o = {-2.0, 0.1, 0.05}, d = {1.0, 0.2, -0.1};
    const double t = 0.8;
    RayDual ray[3];
    for (size_t k = 0; k < 3; ++k) {
        ray[k].v = Interval(o[k] + t * d[k]);
        ray[k].d[0] = Interval(d[k]);
    }
    const RayDual F = torus.evaluate(ray);
    const Gradient3 g = gradientAt(torus, o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2]);
    const double slope = g.d[0] * d[0] + g.d[1] * d[1] + g.d[2] * d[2];
    EXPECT_TRUE(F.v.contains(g.v));
    EXPECT_NEAR(F.d[0].mid(), slope, 1e-12 * (1 + std::abs(slope)));
    EXPECT_LT(F.d[0].width(), 1e-12 * (1 + std::abs(slope)));
}

}  // namespace
}  // namespace strahl
