// The formula compiler: text -> tokens -> expression graph -> register tape.
//
// 1. tokenize() splits the text into numbers, names and operators, keeping
//    each token's byte offset for "column N" messages.
// 2. Parser is a recursive-descent parser, one function per precedence level.
//    It does not build a syntax tree: it calls the Graph's constructors, which
//    fold constant operands on the spot (computing in double with the same
//    num:: functions the evaluator uses), merge constants into an operand's
//    immediate (x*2*pi is x*6.28...), pick the instruction with an immediate
//    for a constant operand (x - 2 becomes AddImm -2, x^3 becomes PowiImm 3)
//    and return the existing node for a subexpression seen before. The graph
//    is a DAG of operations whose only constants are immediates.
// 3. TapeBuilder fuses a product or square that only an addition uses into it
//    (x*y + z is one MulAdd, x^2 + y^2 one SqrAddSqr), then walks the DAG from
//    the result, operands first (the operand needing more registers first,
//    which keeps the peak small), and gives each value the lowest free
//    register; a register is freed after the last use of its value. Inputs
//    live in the first registers and are never overwritten; a Return ends the
//    tape.

#include "strahl/geometry/formula.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <string>
#include <system_error>
#include <tuple>
#include <utility>
#include <vector>

#include "strahl/core/error.h"

namespace strahl {

using formula_detail::Instruction;
using formula_detail::Op;

namespace {

// Parentheses, calls, signs and exponents inside each other: bounds the
// parser's recursion.
constexpr int kMaxNesting = 100;
// The longest chain of operations (a sum of 1000 terms is a chain of 1000
// additions): bounds the recursion of the tape builder.
constexpr int kMaxChain = 1000;
// Integer exponents up to this size use powi (exact repeated multiplication,
// valid for negative bases); larger ones go through powr.
constexpr double kMaxIntegerExponent = 1 << 30;

// ---- positions and messages ------------------------------------------------

// The 1-based column of byte `offset`, counting UTF-8 characters.
size_t columnAt(std::string_view text, size_t offset) {
    size_t column = 1;
    for (size_t i = 0; i < offset && i < text.size(); ++i)
        if ((static_cast<unsigned char>(text[i]) & 0xC0) != 0x80) ++column;
    return column;
}

template <typename... Args>
[[noreturn]] void failAt(std::string_view text, size_t offset, const Args&... args) {
    fail("column ", columnAt(text, offset), ": ", args...);
}

// The whole UTF-8 character starting at `offset`, for quoting it.
std::string_view characterAt(std::string_view text, size_t offset) {
    const auto lead = static_cast<unsigned char>(text[offset]);
    const size_t length = lead >= 0xF0 ? 4 : lead >= 0xE0 ? 3 : lead >= 0xC0 ? 2 : 1;
    return text.substr(offset, length);
}

// A subexpression quoted in a message, shortened if long.
std::string quote(std::string_view text, size_t begin, size_t end) {
    std::string_view part = text.substr(begin, end - begin);
    if (part.size() > 40) return "'" + std::string(part.substr(0, 37)) + "...'";
    return "'" + std::string(part) + "'";
}

bool isDigit(char c) {
    return c >= '0' && c <= '9';
}
bool isNameStart(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
}
bool isNameChar(char c) {
    return isNameStart(c) || isDigit(c);
}
bool isSpace(char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
}
bool isName(std::string_view s) {
    return !s.empty() && isNameStart(s[0]) && std::all_of(s.begin(), s.end(), isNameChar);
}

// ---- the language's names ---------------------------------------------------

struct Function {
    std::string_view name;
    Op op;
    size_t minArguments, maxArguments;
};
constexpr size_t kAny = std::numeric_limits<size_t>::max();
// Alphabetical, as listed in messages.
constexpr Function kFunctions[] = {
    {"abs", Op::Abs, 1, 1},    {"atan", Op::Atan, 1, 1}, {"cos", Op::Cos, 1, 1},
    {"exp", Op::Exp, 1, 1},    {"log", Op::Log, 1, 1},   {"max", Op::Max, 2, kAny},
    {"min", Op::Min, 2, kAny}, {"pow", Op::Powr, 2, 2},  {"sin", Op::Sin, 1, 1},
    {"sqr", Op::Sqr, 1, 1},    {"sqrt", Op::Sqrt, 1, 1}, {"tan", Op::Tan, 1, 1},
};

struct Constant {
    std::string_view name;
    double value;
};
constexpr Constant kConstants[] = {{"e", std::numbers::e}, {"pi", std::numbers::pi}};

const Function* findFunction(std::string_view name) {
    for (const Function& f : kFunctions)
        if (f.name == name) return &f;
    return nullptr;
}
const Constant* findConstant(std::string_view name) {
    for (const Constant& c : kConstants)
        if (c.name == name) return &c;
    return nullptr;
}

// Everything a name in the text can refer to.
struct Names {
    std::span<const std::string> variables;
    const std::map<std::string, double>& parameters;

    std::optional<size_t> variable(std::string_view name) const {
        for (size_t i = 0; i < variables.size(); ++i)
            if (variables[i] == name) return i;
        return std::nullopt;
    }
    const double* parameter(std::string_view name) const {
        const auto it = parameters.find(std::string(name));
        return it == parameters.end() ? nullptr : &it->second;
    }

    // "variables: x, y, z; parameters: R, r; constants: e, pi; functions: ..."
    std::string listing() const {
        auto list = [](const auto& items, auto nameOf) {
            std::string s;
            for (const auto& item : items) s += (s.empty() ? "" : ", ") + std::string(nameOf(item));
            return s.empty() ? std::string("none") : s;
        };
        return "variables: " + list(variables, [](const std::string& v) { return v; }) +
               "; parameters: " + list(parameters, [](const auto& p) { return p.first; }) +
               "; constants: " + list(kConstants, [](const Constant& c) { return c.name; }) +
               "; functions: " + list(kFunctions, [](const Function& f) { return f.name; });
    }

    // " (did you mean 'pi'?)" when a known name differs only in letter case.
    std::string suggestion(std::string_view name) const {
        auto sameIgnoringCase = [&](std::string_view known) {
            return known.size() == name.size() &&
                   std::equal(known.begin(), known.end(), name.begin(), [](char a, char b) {
                       return std::tolower(static_cast<unsigned char>(a)) ==
                              std::tolower(static_cast<unsigned char>(b));
                   });
        };
        std::vector<std::string_view> known(variables.begin(), variables.end());
        for (const auto& p : parameters) known.push_back(p.first);
        for (const Constant& c : kConstants) known.push_back(c.name);
        for (const Function& f : kFunctions) known.push_back(f.name);
        for (std::string_view k : known)
            if (sameIgnoringCase(k)) return " (did you mean '" + std::string(k) + "'?)";
        return {};
    }
};

void checkNames(std::span<const std::string> variables,
                const std::map<std::string, double>& parameters) {
    if (variables.size() > Formula::kMaxRegisters)
        fail("a formula takes at most ", Formula::kMaxRegisters, " variables, got ",
             variables.size());
    for (size_t i = 0; i < variables.size(); ++i) {
        const std::string& v = variables[i];
        if (!isName(v)) fail("variable '", v, "' is not a valid name");
        if (findFunction(v) || findConstant(v))
            fail("variable '", v, "' has the name of a ",
                 findFunction(v) ? "function" : "constant");
        if (std::find(variables.begin(), variables.begin() + static_cast<ptrdiff_t>(i), v) !=
            variables.begin() + static_cast<ptrdiff_t>(i))
            fail("variable '", v, "' is listed twice");
    }
    for (const auto& [name, value] : parameters) {
        if (!isName(name))
            fail("parameter '", name,
                 "' is not a valid name (letters, digits and '_', not "
                 "starting with a digit)");
        if (std::find(variables.begin(), variables.end(), name) != variables.end())
            fail("parameter '", name, "' shadows the variable '", name, "'");
        if (findConstant(name)) fail("parameter '", name, "' shadows the constant '", name, "'");
        if (findFunction(name)) fail("parameter '", name, "' shadows the function '", name, "'");
        if (!std::isfinite(value)) fail("parameter '", name, "' is not finite (", value, ")");
    }
}

// ---- tokens -------------------------------------------------------------------

// clang-format off
enum class TokenKind {
    Number, Name, Plus, Minus, Star, Slash, Caret, LeftParen, RightParen, Comma, End
};
// clang-format on

struct Token {
    TokenKind kind;
    size_t offset;  // byte offset of the first character
    size_t length;  // bytes
    double number;  // the value of a Number
};

// A number: digits with an optional fraction (1, 1.5, .5, 1.) and an optional
// exponent (1e-3, 2.5E+2). The letter e right after a number always starts an
// exponent, so "2e" is a malformed number rather than "2 times e".
Token scanNumber(std::string_view text, size_t start) {
    size_t i = start;
    auto skipDigits = [&] {
        const size_t from = i;
        while (i < text.size() && isDigit(text[i])) ++i;
        return i - from;
    };
    size_t mantissaDigits = skipDigits();
    if (i < text.size() && text[i] == '.') {
        ++i;
        mantissaDigits += skipDigits();
    }
    if (mantissaDigits == 0) failAt(text, start, "malformed number '.'");
    if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
        ++i;
        if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
        if (skipDigits() == 0)
            failAt(text, start, "malformed number ", quote(text, start, i),
                   ": the exponent needs digits");
    }
    if (i < text.size() && (text[i] == '.' || isDigit(text[i]))) {  // 1.2.3, 1e5.5
        while (i < text.size() && (text[i] == '.' || isDigit(text[i]))) ++i;
        failAt(text, start, "malformed number ", quote(text, start, i));
    }
    double value = 0.0;
    const auto result = std::from_chars(text.data() + start, text.data() + i, value);
    if (result.ec != std::errc() || !std::isfinite(value))
        failAt(text, start, "number ", quote(text, start, i), " is out of the range of double");
    return {TokenKind::Number, start, i - start, value};
}

std::vector<Token> tokenize(std::string_view text) {
    std::vector<Token> tokens;
    size_t i = 0;
    while (true) {
        while (i < text.size() && isSpace(text[i])) ++i;
        if (i == text.size()) break;
        const char c = text[i];
        if (isDigit(c) || c == '.') {
            tokens.push_back(scanNumber(text, i));
        } else if (isNameStart(c)) {
            size_t end = i + 1;
            while (end < text.size() && isNameChar(text[end])) ++end;
            tokens.push_back({TokenKind::Name, i, end - i, 0.0});
        } else {
            TokenKind kind{};
            switch (c) {
                // clang-format off
                case '+': kind = TokenKind::Plus; break;
                case '-': kind = TokenKind::Minus; break;
                case '*': kind = TokenKind::Star; break;
                case '/': kind = TokenKind::Slash; break;
                case '^': kind = TokenKind::Caret; break;
                case '(': kind = TokenKind::LeftParen; break;
                case ')': kind = TokenKind::RightParen; break;
                case ',': kind = TokenKind::Comma; break;
                // clang-format on
                case '=':
                    failAt(text, i,
                           "unexpected character '=': write the expression only "
                           "(a - b rather than a = b)");
                default:
                    failAt(text, i, "unexpected character '", characterAt(text, i), "'");
            }
            tokens.push_back({kind, i, 1, 0.0});
        }
        i += tokens.back().length;
    }
    if (tokens.empty()) failAt(text, 0, "empty formula");
    tokens.push_back({TokenKind::End, text.size(), 0, 0.0});
    return tokens;
}

// ---- the expression graph ---------------------------------------------------------

// Where a subexpression is in the text: [begin, end) in bytes.
struct Span {
    size_t begin, end;
};

struct Node {
    enum class Kind : uint8_t { Constant, Variable, Operation };
    Kind kind;
    Op op;
    int a, b, c;      // operand nodes, -1 if none (c only in fused instructions)
    double imm;       // the constant's value, or the immediate of the operation
    size_t variable;  // input index of a Variable
    size_t offset;    // where the subexpression starts, for messages
    int chain;        // length of the longest operation chain ending here
};

// The value of an instruction whose operands are constants, with the
// evaluator's own double arithmetic.
double apply(Op op, double a, double b, double imm) {
    switch (op) {
        // clang-format off
        case Op::Return: return a;
        case Op::Const: return imm;
        case Op::Add: return a + b;
        case Op::Sub: return a - b;
        case Op::Mul: return a * b;
        case Op::Div: return a / b;
        case Op::Min: return num::min(a, b);
        case Op::Max: return num::max(a, b);
        case Op::Powr: return num::powr(a, b);
        case Op::AddImm: return a + imm;
        case Op::MulImm: return a * imm;
        case Op::DivImm: return a / imm;
        case Op::MinImm: return num::min(a, imm);
        case Op::MaxImm: return num::max(a, imm);
        case Op::PowiImm: return num::powi(a, static_cast<int>(imm));
        case Op::PowrImm: return num::powr(a, imm);
        case Op::SubImmLeft: return imm - a;
        case Op::DivImmLeft: return imm / a;
        case Op::PowrImmLeft: return num::powr(imm, a);
        case Op::Neg: return -a;
        case Op::Sqr: return num::sqr(a);
        case Op::Sqrt: return num::sqrt(a);
        case Op::Abs: return num::abs(a);
        case Op::Exp: return num::exp(a);
        case Op::Log: return num::log(a);
        case Op::Sin: return num::sin(a);
        case Op::Cos: return num::cos(a);
        case Op::Tan: return num::tan(a);
        case Op::Atan: return num::atan(a);
        case Op::SqrAddSqr:  // fused instructions: the tape builder makes them, the graph never
        case Op::Hypot:
        case Op::AddSqr:
        case Op::AddShiftedSqr:
        case Op::SqrAddImm:
        case Op::MulAdd:
        case Op::MulImmAdd: break;
            // clang-format on
    }
    return 0.0;
}

// The nodes of the formula, built bottom-up by the parser. Every constructor
// folds constants and reuses an identical node if there is one.
class Graph {
public:
    explicit Graph(std::string_view text) : text_(text) {}

    const Node& node(int index) const { return nodes_[static_cast<size_t>(index)]; }
    const std::vector<Node>& nodes() const { return nodes_; }
    bool isConstant(int index) const { return node(index).kind == Node::Kind::Constant; }
    double value(int index) const { return node(index).imm; }

    int constant(double value, Span span) {
        if (!std::isfinite(value))
            failAt(text_, span.begin, quote(text_, span.begin, span.end), " evaluates to ", value,
                   " (a constant must be finite)");
        return intern({Node::Kind::Constant, Op::Const, -1, -1, -1, value, 0, span.begin, 0});
    }

    int variable(size_t index, Span span) {
        return intern({Node::Kind::Variable, Op::Const, -1, -1, -1, 0.0, index, span.begin, 0});
    }

    // An operation of one operand: Neg or a function of one argument.
    int unary(Op op, int a, Span span) {
        if (isConstant(a)) return constant(apply(op, value(a), 0.0, 0.0), span);
        const Node& operand = node(a);
        if (op == Op::Neg && operand.kind == Node::Kind::Operation) {
            // Each of these is exact: negation only flips a sign.
            const int x = operand.a;
            const double k = operand.imm;
            switch (operand.op) {
                case Op::Neg:
                    return x;  // --x
                case Op::MulImm:
                    return operation(Op::MulImm, x, -1, -k, span);  // -(x*k)
                case Op::DivImm:
                    return operation(Op::DivImm, x, -1, -k, span);  // -(x/k)
                case Op::AddImm:
                    return operation(Op::SubImmLeft, x, -1, -k, span);  // -(x+k)
                case Op::SubImmLeft:
                    return operation(Op::AddImm, x, -1, -k, span);  // -(k-x)
                default:
                    break;
            }
        }
        return operation(op, a, -1, 0.0, span);
    }

    int add(int a, int b, Span span) {
        if (isConstant(a)) std::swap(a, b);
        if (isConstant(b)) return addConstant(a, value(b), span);
        return operation(Op::Add, std::min(a, b), std::max(a, b), 0.0, span);  // a + b = b + a
    }

    int subtract(int a, int b, Span span) {
        if (isConstant(b)) return addConstant(a, -value(b), span);
        if (isConstant(a)) return subtractFromConstant(value(a), b, span);
        return operation(Op::Sub, a, b, 0.0, span);
    }

    int multiply(int a, int b, Span span) {
        if (isConstant(a)) std::swap(a, b);
        if (isConstant(b)) return multiplyByConstant(a, value(b), span);
        if (a == b) return operation(Op::Sqr, a, -1, 0.0, span);  // tighter for intervals
        return operation(Op::Mul, std::min(a, b), std::max(a, b), 0.0, span);
    }

    int divide(int a, int b, Span span, Span divisor) {
        if (isConstant(b) && value(b) == 0.0)
            failAt(text_, divisor.begin, "division by zero (",
                   quote(text_, divisor.begin, divisor.end), " is 0)");
        if (isConstant(a) && isConstant(b)) return constant(value(a) / value(b), span);
        if (isConstant(b)) return divideByConstant(a, value(b), span);
        if (isConstant(a)) return operation(Op::DivImmLeft, b, -1, value(a), span);
        return operation(Op::Div, a, b, 0.0, span);
    }

    // a^b and pow(a, b): an integer constant exponent uses powi, anything else powr.
    int power(int a, int b, Span span) {
        if (isConstant(b)) {
            const double exponent = value(b);
            const bool integer =
                exponent == std::trunc(exponent) && std::abs(exponent) <= kMaxIntegerExponent;
            const Op op = integer ? Op::PowiImm : Op::PowrImm;
            if (isConstant(a)) return constant(apply(op, value(a), 0.0, exponent), span);
            if (integer && exponent == 0.0) return constant(1.0, span);  // powi(x, 0) is 1
            if (integer && exponent == 1.0) return a;
            if (integer && exponent == 2.0) return operation(Op::Sqr, a, -1, 0.0, span);
            if (integer && exponent == -1.0) return operation(Op::DivImmLeft, a, -1, 1.0, span);
            return operation(op, a, -1, exponent, span);
        }
        if (isConstant(a)) return operation(Op::PowrImmLeft, b, -1, value(a), span);
        return operation(Op::Powr, a, b, 0.0, span);
    }

    // min or max of two operands (the parser folds constants of longer lists).
    int extremum(Op op, int a, int b, Span span) {
        const Op withImmediate = op == Op::Min ? Op::MinImm : Op::MaxImm;
        if (isConstant(a) && isConstant(b))
            return constant(apply(op, value(a), value(b), 0.0), span);
        if (isConstant(a)) std::swap(a, b);
        if (isConstant(b)) return operation(withImmediate, a, -1, value(b), span);
        if (a == b) return a;
        // Not reordered: at a tie, a dual keeps the derivatives of its first operand.
        return operation(op, a, b, 0.0, span);
    }

private:
    // The constructors below merge a constant into the immediate of an operand
    // that has one: (x + 1) - 3 is x - 2 and x*2*pi is x*(2*pi), one
    // instruction. This reassociates, so the last bit may differ from strict
    // left-to-right evaluation; a merged constant that is not a normal number
    // is not merged.
    static bool mergeable(double merged) { return std::isnormal(merged); }
    bool isOperation(int index, Op op) const {
        return node(index).kind == Node::Kind::Operation && node(index).op == op;
    }

    // a + c
    int addConstant(int a, double c, Span span) {
        if (isConstant(a)) return constant(value(a) + c, span);
        if (c == 0.0) return a;
        const int x = node(a).a;
        const double k = node(a).imm;
        if (isOperation(a, Op::AddImm) && (k + c == 0.0 || mergeable(k + c)))
            return addConstant(x, k + c, span);  // (x + k) + c
        if (isOperation(a, Op::SubImmLeft) && (k + c == 0.0 || mergeable(k + c)))
            return subtractFromConstant(k + c, x, span);  // (k - x) + c
        return operation(Op::AddImm, a, -1, c, span);
    }

    // c - a
    int subtractFromConstant(double c, int a, Span span) {
        const int x = node(a).a;
        const double k = node(a).imm;
        if (isOperation(a, Op::AddImm) && (c - k == 0.0 || mergeable(c - k)))
            return subtractFromConstant(c - k, x, span);  // c - (x + k)
        if (isOperation(a, Op::SubImmLeft) && (c - k == 0.0 || mergeable(c - k)))
            return addConstant(x, c - k, span);  // c - (k - x)
        if (c == 0.0) return unary(Op::Neg, a, span);
        return operation(Op::SubImmLeft, a, -1, c, span);
    }

    // a * c
    int multiplyByConstant(int a, double c, Span span) {
        if (isConstant(a)) return constant(value(a) * c, span);
        if (c == 1.0) return a;
        if (c == -1.0) return unary(Op::Neg, a, span);
        const int x = node(a).a;
        const double k = node(a).imm;
        if (isOperation(a, Op::MulImm) && mergeable(k * c))
            return multiplyByConstant(x, k * c, span);  // (x * k) * c
        if (isOperation(a, Op::DivImm) && mergeable(c / k))
            return multiplyByConstant(x, c / k, span);  // (x / k) * c
        if (isOperation(a, Op::DivImmLeft) && mergeable(k * c))
            return operation(Op::DivImmLeft, x, -1, k * c, span);  // (k / x) * c
        return operation(Op::MulImm, a, -1, c, span);
    }

    // a / c, c != 0
    int divideByConstant(int a, double c, Span span) {
        if (c == 1.0) return a;
        if (c == -1.0) return unary(Op::Neg, a, span);
        const int x = node(a).a;
        const double k = node(a).imm;
        if (isOperation(a, Op::MulImm) && mergeable(k / c))
            return multiplyByConstant(x, k / c, span);  // (x * k) / c
        if (isOperation(a, Op::DivImm) && mergeable(k * c))
            return divideByConstant(x, k * c, span);  // (x / k) / c
        if (isOperation(a, Op::DivImmLeft) && mergeable(k / c))
            return operation(Op::DivImmLeft, x, -1, k / c, span);  // (k / x) / c
        return operation(Op::DivImm, a, -1, c, span);
    }

    int operation(Op op, int a, int b, double imm, Span span) {
        return intern({Node::Kind::Operation, op, a, b, -1, imm, 0, span.begin, 0});
    }

    // The index of an identical node if there is one, else of the new node.
    int intern(Node n) {
        uint64_t immBits = 0;
        std::memcpy(&immBits, &n.imm, sizeof immBits);
        const auto key = std::make_tuple(n.kind, n.op, n.a, n.b, immBits, n.variable);
        if (const auto it = index_.find(key); it != index_.end()) return it->second;
        if (n.kind == Node::Kind::Operation) {
            n.chain = 1 + std::max(node(n.a).chain, n.b >= 0 ? node(n.b).chain : 0);
            if (n.chain > kMaxChain)
                failAt(text_, n.offset,
                       "formula is too deeply nested for the evaluator (a chain "
                       "of more than ",
                       kMaxChain, " operations)");
        }
        nodes_.push_back(n);
        const int index = static_cast<int>(nodes_.size() - 1);
        index_.emplace(key, index);
        return index;
    }

    std::string_view text_;
    std::vector<Node> nodes_;
    std::map<std::tuple<Node::Kind, Op, int, int, uint64_t, size_t>, int> index_;
};

// ---- the parser -------------------------------------------------------------------
//
//   formula    := sum END
//   sum        := product (('+' | '-') product)*
//   product    := signed (('*' | '/') signed)*
//   signed     := ('-' | '+') signed | power
//   power      := primary ('^' signed)?          right-associative, above the sign
//   primary    := NUMBER | NAME | NAME '(' arguments ')' | '(' sum ')'
//   arguments  := (sum (',' sum)*)?

// A parsed subexpression: its node and where it is in the text.
struct Parsed {
    int node;
    Span span;
};

class Parser {
public:
    Parser(std::string_view text, std::vector<Token> tokens, const Names& names, Graph& graph)
        : text_(text), tokens_(std::move(tokens)), names_(names), graph_(graph) {}

    int parseFormula() {
        const Parsed result = parseSum();
        const Token& token = peek();
        if (token.kind == TokenKind::RightParen) failAt(text_, token.offset, "unmatched ')'");
        if (token.kind != TokenKind::End)
            failAfterOperand(token, "an operator or the end of the formula");
        return result.node;
    }

private:
    // Counts the nesting of signed(), which every level of parentheses, call,
    // sign and exponent passes through.
    class NestingGuard {
    public:
        explicit NestingGuard(Parser& parser) : parser_(parser) {
            if (++parser_.nesting_ > kMaxNesting)
                failAt(parser_.text_, parser_.peek().offset,
                       "formula is too deeply nested (more "
                       "than ",
                       kMaxNesting, " levels of parentheses, calls, signs or exponents)");
        }
        ~NestingGuard() { --parser_.nesting_; }
        NestingGuard(const NestingGuard&) = delete;
        NestingGuard& operator=(const NestingGuard&) = delete;

    private:
        Parser& parser_;
    };

    const Token& peek() const { return tokens_[position_]; }
    const Token& next() { return tokens_[position_++]; }  // End is never passed
    std::string_view lexeme(const Token& t) const { return text_.substr(t.offset, t.length); }

    std::string describe(const Token& t) const {
        if (t.kind == TokenKind::End) return "the end of the formula";
        return "'" + std::string(lexeme(t)) + "'";
    }

    [[noreturn]] void failExpectedOperand(const Token& t) const {
        failAt(text_, t.offset, "expected an operand (a number, a name or '('), found ",
               describe(t));
    }

    // After a complete operand, `t` is neither an operator nor what `expected`
    // names.
    [[noreturn]] void failAfterOperand(const Token& t, std::string_view expected) const {
        if (t.kind == TokenKind::Number || t.kind == TokenKind::Name ||
            t.kind == TokenKind::LeftParen)
            failAt(text_, t.offset, "expected an operator, found ", describe(t),
                   " (a product needs an explicit '*')");
        failAt(text_, t.offset, "expected ", expected, ", found ", describe(t));
    }

    Parsed parseSum() {
        Parsed left = parseProduct();
        while (peek().kind == TokenKind::Plus || peek().kind == TokenKind::Minus) {
            const bool plus = next().kind == TokenKind::Plus;
            const Parsed right = parseProduct();
            const Span span{left.span.begin, right.span.end};
            left = {plus ? graph_.add(left.node, right.node, span)
                         : graph_.subtract(left.node, right.node, span),
                    span};
        }
        return left;
    }

    Parsed parseProduct() {
        Parsed left = parseSigned();
        while (peek().kind == TokenKind::Star || peek().kind == TokenKind::Slash) {
            const bool times = next().kind == TokenKind::Star;
            const Parsed right = parseSigned();
            const Span span{left.span.begin, right.span.end};
            left = {times ? graph_.multiply(left.node, right.node, span)
                          : graph_.divide(left.node, right.node, span, right.span),
                    span};
        }
        return left;
    }

    Parsed parseSigned() {
        const NestingGuard guard(*this);
        if (peek().kind == TokenKind::Minus || peek().kind == TokenKind::Plus) {
            const Token& sign = next();
            const Parsed operand = parseSigned();
            const Span span{sign.offset, operand.span.end};
            if (sign.kind == TokenKind::Plus) return {operand.node, span};
            return {graph_.unary(Op::Neg, operand.node, span), span};
        }
        return parsePower();
    }

    Parsed parsePower() {
        const Parsed base = parsePrimary();
        if (peek().kind != TokenKind::Caret) return base;
        next();
        const Parsed exponent = parseSigned();  // right-associative: 2^3^2 = 2^9
        const Span span{base.span.begin, exponent.span.end};
        return {graph_.power(base.node, exponent.node, span), span};
    }

    Parsed parsePrimary() {
        const Token& token = peek();
        switch (token.kind) {
            case TokenKind::Number: {
                next();
                const Span span{token.offset, token.offset + token.length};
                return {graph_.constant(token.number, span), span};
            }
            case TokenKind::Name:
                return parseName();
            case TokenKind::LeftParen: {
                const Token& open = next();
                const Parsed inner = parseSum();
                if (peek().kind != TokenKind::RightParen)
                    failAfterOperand(peek(), "')' to close the '(' at column " +
                                                 std::to_string(columnAt(text_, open.offset)));
                const Token& close = next();
                return {inner.node, Span{open.offset, close.offset + 1}};
            }
            default:
                failExpectedOperand(token);
        }
    }

    Parsed parseName() {
        const Token& token = next();
        const std::string_view name = lexeme(token);
        if (peek().kind == TokenKind::LeftParen) return parseCall(token);
        const Span span{token.offset, token.offset + token.length};
        if (const auto index = names_.variable(name)) return {graph_.variable(*index, span), span};
        if (const double* value = names_.parameter(name))
            return {graph_.constant(*value, span), span};
        if (const Constant* c = findConstant(name)) return {graph_.constant(c->value, span), span};
        if (findFunction(name))
            failAt(text_, token.offset, "'", name, "' is a function: call it as ", name, "(...)");
        failAt(text_, token.offset, "unknown name '", name, "'", names_.suggestion(name), "; ",
               names_.listing());
    }

    Parsed parseCall(const Token& nameToken) {
        const std::string_view name = lexeme(nameToken);
        const Function* function = findFunction(name);
        if (!function) {
            const char* kind = names_.variable(name)    ? "a variable"
                               : names_.parameter(name) ? "a parameter"
                               : findConstant(name)     ? "a constant"
                                                        : nullptr;
            if (kind)
                failAt(text_, nameToken.offset, "'", name, "' is ", kind,
                       ", not a function (a product needs an explicit '*')");
            failAt(text_, nameToken.offset, "unknown function '", name, "'",
                   names_.suggestion(name), "; ", names_.listing());
        }
        const Token& open = next();
        std::vector<Parsed> arguments;
        if (peek().kind != TokenKind::RightParen) {
            while (true) {
                arguments.push_back(parseSum());
                if (peek().kind == TokenKind::Comma) {
                    next();
                    continue;
                }
                if (peek().kind == TokenKind::RightParen) break;
                failAfterOperand(peek(), "',' or ')' to close the '(' of " + std::string(name) +
                                             " at column " +
                                             std::to_string(columnAt(text_, open.offset)));
            }
        }
        const Token& close = next();
        checkArgumentCount(*function, arguments.size(), nameToken);
        const Span span{nameToken.offset, close.offset + 1};

        if (function->op == Op::Min || function->op == Op::Max)
            return {extremum(function->op, arguments, span), span};
        if (function->op == Op::Powr)
            return {graph_.power(arguments[0].node, arguments[1].node, span), span};
        return {graph_.unary(function->op, arguments[0].node, span), span};
    }

    void checkArgumentCount(const Function& f, size_t count, const Token& nameToken) const {
        if (count >= f.minArguments && count <= f.maxArguments) return;
        const auto plural = [](size_t n) { return n == 1 ? " argument" : " arguments"; };
        if (f.maxArguments == kAny)
            failAt(text_, nameToken.offset, f.name, " takes at least ", f.minArguments,
                   plural(f.minArguments), ", got ", count);
        failAt(text_, nameToken.offset, f.name, " takes ", f.minArguments, plural(f.minArguments),
               ", got ", count);
    }

    // min/max of any number of arguments: the constant ones are folded into one
    // immediate, the others are chained left to right.
    int extremum(Op op, const std::vector<Parsed>& arguments, Span span) {
        int result = -1, constant = -1;
        for (const Parsed& argument : arguments) {
            int& slot = graph_.isConstant(argument.node) ? constant : result;
            slot = slot < 0 ? argument.node : graph_.extremum(op, slot, argument.node, span);
        }
        if (result < 0) return constant;
        return constant < 0 ? result : graph_.extremum(op, result, constant, span);
    }

    std::string_view text_;
    std::vector<Token> tokens_;
    const Names& names_;
    Graph& graph_;
    size_t position_ = 0;
    int nesting_ = 0;
};

// ---- the tape -----------------------------------------------------------------------

class TapeBuilder {
public:
    TapeBuilder(std::string_view text, std::vector<Node> nodes, size_t variableCount)
        : text_(text),
          nodes_(std::move(nodes)),
          variableCount_(variableCount),
          remainingUses_(nodes_.size(), 0),
          register_(nodes_.size(), -1),
          need_(nodes_.size(), -1),
          busy_(Formula::kMaxRegisters, false),
          usedVariables_(variableCount, false) {}

    void build(int root) {
        countUses(root);
        ++remainingUses_[index(root)];  // the result stays live to the end
        for (size_t i = 0; i < nodes_.size(); ++i)
            if (remainingUses_[i] > 0 && nodes_[i].kind == Node::Kind::Operation) fuse(nodes_[i]);
        const uint8_t result = emit(root);
        tape.push_back({Op::Return, 0, result, 0, 0, 0.0});
    }

    std::vector<Instruction> tape;
    size_t registerCount() const { return std::max(variableCount_, highWater_); }
    const std::vector<bool>& usedVariables() const { return usedVariables_; }

private:
    static size_t index(int node) { return static_cast<size_t>(node); }
    Node& node(int i) { return nodes_[index(i)]; }

    // How often each reachable node is an operand, and which inputs are used.
    void countUses(int i) {
        const Node& n = node(i);
        if (n.kind == Node::Kind::Variable) usedVariables_[n.variable] = true;
        for (const int operand : {n.a, n.b}) {
            if (operand < 0) continue;
            if (remainingUses_[index(operand)]++ == 0) countUses(operand);
        }
    }

    bool isSingleUse(int i, Op op) {
        return i >= 0 && node(i).kind == Node::Kind::Operation && node(i).op == op &&
               remainingUses_[index(i)] == 1;
    }

    // Merges a product or square that only an addition uses into it: one
    // dispatch instead of two or three, same arithmetic. Consumed nodes are dead.
    void fuse(Node& n) {
        // Operands are fused before the nodes that use them (they come first
        // in the node list), so a square root sees a fused sum of squares.
        if (n.op == Op::Sqrt && isSingleUse(n.a, Op::SqrAddSqr)) {  // sqrt(a^2 + b^2)
            const Node& sum = node(n.a);
            consume(n.a);
            n.op = Op::Hypot;
            n.b = sum.b;
            n.a = sum.a;
            return;
        }
        if (n.op == Op::AddImm && isSingleUse(n.a, Op::Sqr)) {  // a^2 + k
            consume(n.a);
            n.op = Op::SqrAddImm;
            n.a = node(n.a).a;
            return;
        }
        if (n.op == Op::Add && isSingleUse(n.a, Op::Sqr) && isSingleUse(n.b, Op::Sqr) &&
            !isShiftedSquare(n.a) && !isShiftedSquare(n.b)) {  // a^2 + b^2
            consume(n.a);
            consume(n.b);
            n.op = Op::SqrAddSqr;
            n.a = node(n.a).a;
            n.b = node(n.b).a;
            return;
        }
        if (n.op == Op::Add) {
            for (const auto& [other, candidate] : {std::pair{n.a, n.b}, std::pair{n.b, n.a}}) {
                const Node& m = node(candidate);
                if (isSingleUse(candidate, Op::Mul)) {  // a*b + c
                    n.op = Op::MulAdd;
                    n.a = m.a;
                    n.b = m.b;
                    n.c = other;
                } else if (isSingleUse(candidate, Op::MulImm)) {  // a*k + b
                    n.op = Op::MulImmAdd;
                    n.a = m.a;
                    n.b = other;
                    n.imm = m.imm;
                } else if (isShiftedSquare(candidate)) {  // a + (b + k)^2
                    const Node& shift = node(m.a);
                    consume(m.a);
                    n.op = Op::AddShiftedSqr;
                    n.a = other;
                    n.b = shift.a;
                    n.imm = shift.imm;
                } else if (isSingleUse(candidate, Op::Sqr)) {  // a + b^2
                    n.op = Op::AddSqr;
                    n.a = other;
                    n.b = m.a;
                } else {
                    continue;
                }
                consume(candidate);
                return;
            }
        }
        if (n.op == Op::Sub && isSingleUse(n.b, Op::MulImm)) {  // a - b*k = b*(-k) + a, exactly
            const Node& m = node(n.b);
            consume(n.b);
            n.op = Op::MulImmAdd;
            n.b = n.a;
            n.a = m.a;
            n.imm = -m.imm;
        }
    }

    // (b + k)^2 with both parts used only there.
    bool isShiftedSquare(int i) {
        return isSingleUse(i, Op::Sqr) && isSingleUse(node(i).a, Op::AddImm);
    }

    // Node i is now computed inside the instruction that used it; its
    // operands are used by that instruction instead.
    void consume(int i) { remainingUses_[index(i)] = 0; }

    std::vector<int> operandsOf(const Node& n) const {
        std::vector<int> operands;
        for (const int operand : {n.a, n.b, n.c})
            if (operand >= 0) operands.push_back(operand);
        return operands;
    }

    // Registers needed to compute a node (Sethi-Ullman number, sharing ignored):
    // operands in decreasing need, each earlier result held while the next is
    // computed.
    int need(int i) {
        int& memo = need_[index(i)];
        if (memo >= 0) return memo;
        const Node& n = node(i);
        if (n.kind == Node::Kind::Variable) return memo = 0;
        if (n.kind == Node::Kind::Constant) return memo = 1;
        std::vector<int> needs;
        for (const int operand : operandsOf(n)) needs.push_back(need(operand));
        std::sort(needs.begin(), needs.end(), std::greater<>());
        int result = 1;
        for (size_t k = 0; k < needs.size(); ++k)
            result = std::max(result, needs[k] + static_cast<int>(k));
        return memo = result;
    }

    uint8_t emit(int i) {
        if (register_[index(i)] >= 0) return static_cast<uint8_t>(register_[index(i)]);
        const Node& n = node(i);
        if (n.kind == Node::Kind::Variable) return assign(i, n.variable);
        if (n.kind == Node::Kind::Constant) {  // only a formula that is constant as a whole
            const uint8_t dst = allocate(i);
            tape.push_back({Op::Const, dst, 0, 0, 0, n.imm});
            return dst;
        }
        // The operand that needs more registers first: its temporaries are
        // free again before the next operand is computed.
        std::vector<int> operands = operandsOf(n);
        std::vector<int> order = operands;
        std::stable_sort(order.begin(), order.end(),
                         [&](int x, int y) { return need(x) > need(y); });
        for (const int operand : order) emit(operand);
        uint8_t reg[3] = {0, 0, 0};
        for (size_t k = 0; k < operands.size(); ++k)
            reg[k] = static_cast<uint8_t>(register_[index(operands[k])]);
        for (const int operand : operands) release(operand);
        const uint8_t dst = allocate(i);  // may reuse an operand's register
        tape.push_back({n.op, dst, reg[0], reg[1], reg[2], n.imm});
        return dst;
    }

    uint8_t assign(int i, size_t reg) {
        register_[index(i)] = static_cast<int>(reg);
        return static_cast<uint8_t>(reg);
    }

    uint8_t allocate(int i) {
        for (size_t reg = variableCount_; reg < Formula::kMaxRegisters; ++reg) {
            if (busy_[reg]) continue;
            busy_[reg] = true;
            highWater_ = std::max(highWater_, reg + 1);
            return assign(i, reg);
        }
        failAt(text_, node(i).offset,
               "formula is too large for the evaluator (it needs more "
               "than ",
               Formula::kMaxRegisters, " registers)");
    }

    // One use of node i done; its register is free after the last one.
    void release(int i) {
        if (--remainingUses_[index(i)] > 0) return;
        if (node(i).kind == Node::Kind::Variable) return;  // inputs stay
        busy_[static_cast<size_t>(register_[index(i)])] = false;
    }

    std::string_view text_;
    std::vector<Node> nodes_;
    size_t variableCount_;
    std::vector<int> remainingUses_;
    std::vector<int> register_;  // per node, -1 until computed
    std::vector<int> need_;      // per node, -1 until known
    std::vector<bool> busy_;
    std::vector<bool> usedVariables_;
    size_t highWater_ = 0;
};

}  // namespace

Formula Formula::compile(std::string_view text, std::span<const std::string> variables,
                         const std::map<std::string, double>& parameters) {
    checkNames(variables, parameters);
    const Names names{variables, parameters};
    Graph graph(text);
    Parser parser(text, tokenize(text), names, graph);
    const int root = parser.parseFormula();

    TapeBuilder builder(text, graph.nodes(), variables.size());
    builder.build(root);

    Formula formula;
    formula.text_ = std::string(text);
    formula.tape_ = std::move(builder.tape);
    formula.usedVariables_ = builder.usedVariables();
    formula.variableCount_ = variables.size();
    formula.registerCount_ = builder.registerCount();
    return formula;
}

}  // namespace strahl
