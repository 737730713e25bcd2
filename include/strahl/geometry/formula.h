#pragma once
// Formula: user-written math from scene files, such as the implicit torus
// "(x^2 + y^2 + z^2 + R^2 - r^2)^2 - 4*R^2*(x^2 + y^2)". It is parsed once and
// then evaluated millions of times per frame in double, interval and dual
// arithmetic. Syntax reference for users: docs/formulas.md.
//
// The tape: compile() turns the text into a flat list of instructions
// `dst = op(a, b, c, imm)` over a small array of registers, ended by a Return.
// The inputs occupy the first registers. Constant subexpressions are folded and
// end up as the immediate of an instruction (2*pi*x is one MulImm), a product
// or square feeding a sum is fused into it (x*y + z is one MulAdd), a
// subexpression written twice is computed once, and a register is reused as
// soon as its value is dead, so the working set stays small. evaluate<T>()
// runs the tape over a local array of kMaxRegisters values, one jump to the
// code of each instruction (threaded code, or a switch): no allocation, no
// recursion, no virtual calls, so one compiled formula serves every arithmetic
// at close to the speed of the same function written in C++. The compiler is
// in src/geometry/formula.cpp.

#include <cstddef>
#include <cstdint>
#include <iterator>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "strahl/core/dual.h"
#include "strahl/core/interval.h"

namespace strahl {

namespace formula_detail {
struct Instruction;
}

class Formula {
public:
    // Registers of the evaluator, inputs included. A formula that needs more
    // does not compile.
    static constexpr size_t kMaxRegisters = 64;

    // Parses `text` once. `variables` names the inputs in order (e.g. x, y, z);
    // `parameters` are named constants from the scene file (e.g. R = 1). Throws
    // strahl::Error "column N: ..." for a malformed formula; a bad parameter
    // (not a name, not finite, or shadowing a variable, constant or function)
    // throws an Error that names it.
    static Formula compile(std::string_view text, std::span<const std::string> variables,
                           const std::map<std::string, double>& parameters = {});

    // The value at inputs vars[0 .. variableCount() - 1]. T is double,
    // num::Interval, num::Gradient3, num::RayDual, or any type with the num::
    // functions, + - * / and an implicit conversion from double. Const and
    // free of shared state: any number of threads may evaluate one Formula.
    template <class T>
    T evaluate(const T* vars) const;

    size_t variableCount() const { return variableCount_; }
    size_t instructionCount() const;
    // Registers the tape uses, inputs included (at most kMaxRegisters).
    size_t registerCount() const { return registerCount_; }
    const std::string& text() const { return text_; }
    // Whether the value depends on input `index` (after constant folding: x^0
    // does not use x).
    bool usesVariable(size_t index) const {
        return index < usedVariables_.size() && usedVariables_[index];
    }

private:
    Formula() = default;

    std::string text_;
    std::vector<formula_detail::Instruction> tape_;
    std::vector<bool> usedVariables_;
    size_t variableCount_ = 0;
    size_t registerCount_ = 0;
};

// ---- the evaluator --------------------------------------------------------

namespace formula_detail {

// `dst = ...` for every instruction; registers are a, b and c, the constant
// operand is imm. "Left" means the immediate is the left operand.
// clang-format off
enum class Op : uint8_t {
    Return,  // the value is a; the last instruction
    Const,   // imm (only when the whole formula is constant)
    Add, Sub, Mul, Div, Min, Max, Powr,             // a op b
    AddImm, MulImm, DivImm, MinImm, MaxImm,         // a op imm (a - c is AddImm -c)
    PowiImm, PowrImm,                               // a ^ imm, integer or real exponent
    SubImmLeft, DivImmLeft, PowrImmLeft,            // imm op a
    Neg, Sqr, Sqrt, Abs, Exp, Log, Sin, Cos, Tan, Atan,  // f(a)
    // fused: a^2 + b^2, sqrt(a^2 + b^2), a + b^2, a + (b + imm)^2, a^2 + imm,
    // a*b + c, a*imm + b
    SqrAddSqr, Hypot, AddSqr, AddShiftedSqr, SqrAddImm, MulAdd, MulImmAdd,
};
inline constexpr size_t kOpCount = static_cast<size_t>(Op::MulImmAdd) + 1;
// clang-format on

// 16 bytes: four one-byte register indices fit before the immediate.
struct Instruction {
    Op op;
    uint8_t dst, a, b, c;
    double imm;  // the constant operand; an integer for PowiImm
};
static_assert(Formula::kMaxRegisters <= 256, "register indices are one byte");

// Arithmetic with a constant operand. The generic versions convert the
// constant to T; the overloads skip work that the constant makes pointless (the
// zero derivatives of a constant, the four corner products of a point interval).
template <class T>
T addImm(const T& a, double c) {
    return a + T(c);
}
template <class T>
T mulImm(const T& a, double c) {
    return a * T(c);
}
template <class T>
T divImm(const T& a, double c) {
    return a / T(c);
}
template <class T>
T subFromImm(double c, const T& a) {
    return T(c) - a;
}

inline num::Interval mulImm(const num::Interval& a, double c) {
    if (c > 0.0) return num::Interval::rounded(a.lo * c, a.hi * c);
    if (c < 0.0) return num::Interval::rounded(a.hi * c, a.lo * c);
    return a * num::Interval(c);  // 0 * inf bounds are 0, as in the general product
}
// c is never 0: the compiler rejects a division by a constant zero.
inline num::Interval divImm(const num::Interval& a, double c) {
    if (c > 0.0) return num::Interval::rounded(a.lo / c, a.hi / c);
    return num::Interval::rounded(a.hi / c, a.lo / c);
}

template <class T, int N>
num::Dual<T, N> addImm(const num::Dual<T, N>& a, double c) {
    num::Dual<T, N> r = a;
    r.v = addImm(a.v, c);
    return r;
}
template <class T, int N>
num::Dual<T, N> mulImm(const num::Dual<T, N>& a, double c) {
    num::Dual<T, N> r;
    r.v = mulImm(a.v, c);
    for (int i = 0; i < N; ++i) r.d[i] = mulImm(a.d[i], c);
    return r;
}
template <class T, int N>
num::Dual<T, N> divImm(const num::Dual<T, N>& a, double c) {
    num::Dual<T, N> r;
    r.v = divImm(a.v, c);
    for (int i = 0; i < N; ++i) r.d[i] = divImm(a.d[i], c);
    return r;
}
template <class T, int N>
num::Dual<T, N> subFromImm(double c, const num::Dual<T, N>& a) {
    num::Dual<T, N> r;
    r.v = subFromImm(c, a.v);
    for (int i = 0; i < N; ++i) r.d[i] = -a.d[i];
    return r;
}

// The register array. For the usual trivially destructible types it is left
// uninitialised (zeroing 64 duals would cost more than a small formula):
// compile() guarantees that every register is written before it is read.
template <class T, bool = std::is_trivially_destructible_v<T>>
struct Registers {
    T r[Formula::kMaxRegisters];
};
template <class T>
struct Registers<T, true> {
    Registers() {}  // NOLINT: deliberately no initialisation
    union {
        T r[Formula::kMaxRegisters];
    };
};

}  // namespace formula_detail

// The Return at the end is not counted.
inline size_t Formula::instructionCount() const {
    return tape_.size() - 1;
}

// Dispatch. With GCC and Clang the code of each instruction jumps straight to
// the code of the next one through a table of label addresses ("threaded
// code", a GNU extension): a third fewer machine instructions and one jump less
// per instruction than a switch, which makes small formulas 15-25% faster.
// Other compilers, or defining STRAHL_FORMULA_SWITCH_DISPATCH, run the same
// cases in a switch. Both are written once, through the two macros below.
#if defined(__GNUC__) && !defined(STRAHL_FORMULA_SWITCH_DISPATCH)
#define STRAHL_FORMULA_THREADED 1
#else
#define STRAHL_FORMULA_THREADED 0
#endif

template <class T>
T Formula::evaluate(const T* vars) const {
    using formula_detail::Op;
    formula_detail::Registers<T> registers;
    T* regs = registers.r;
    // The inputs, the usual few written out: as a loop the copy becomes a
    // memcpy call, which costs more than a small formula.
    const size_t n = variableCount_;
    if (n > 0) regs[0] = vars[0];
    if (n > 1) regs[1] = vars[1];
    if (n > 2) regs[2] = vars[2];
    for (size_t i = 3; i < n; ++i) regs[i] = vars[i];

    // The tape ends with a Return, so there is no end test. The destination
    // may be an operand: every case computes its value before assigning it.
    const formula_detail::Instruction* in = tape_.data();
    // The operands of the current instruction.
    const auto a = [&]() -> const T& { return regs[in->a]; };
    const auto b = [&]() -> const T& { return regs[in->b]; };
    const auto c = [&]() -> const T& { return regs[in->c]; };
    const auto imm = [&] { return in->imm; };
    const auto dst = [&]() -> T& { return regs[in->dst]; };
#if STRAHL_FORMULA_THREADED
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpedantic"
    // In the order of Op.
    static const void* const kCode[] = {
        &&op_Return,   &&op_Const,      &&op_Add,           &&op_Sub,         &&op_Mul,
        &&op_Div,      &&op_Min,        &&op_Max,           &&op_Powr,        &&op_AddImm,
        &&op_MulImm,   &&op_DivImm,     &&op_MinImm,        &&op_MaxImm,      &&op_PowiImm,
        &&op_PowrImm,  &&op_SubImmLeft, &&op_DivImmLeft,    &&op_PowrImmLeft, &&op_Neg,
        &&op_Sqr,      &&op_Sqrt,       &&op_Abs,           &&op_Exp,         &&op_Log,
        &&op_Sin,      &&op_Cos,        &&op_Tan,           &&op_Atan,        &&op_SqrAddSqr,
        &&op_Hypot,    &&op_AddSqr,     &&op_AddShiftedSqr, &&op_SqrAddImm,   &&op_MulAdd,
        &&op_MulImmAdd};
    static_assert(std::size(kCode) == formula_detail::kOpCount);
#define STRAHL_OP(name) op_##name:
#define STRAHL_NEXT goto* kCode[static_cast<size_t>((++in)->op)]
    goto* kCode[static_cast<size_t>(in->op)];
#else
#define STRAHL_OP(name) case Op::name:
#define STRAHL_NEXT \
    ++in;           \
    continue
    for (;;) {
        switch (in->op) {
#endif
    // clang-format off
    STRAHL_OP(Return) return a();
    STRAHL_OP(Const) dst() = T(imm()); STRAHL_NEXT;
    STRAHL_OP(Add) dst() = a() + b(); STRAHL_NEXT;
    STRAHL_OP(Sub) dst() = a() - b(); STRAHL_NEXT;
    STRAHL_OP(Mul) dst() = a() * b(); STRAHL_NEXT;
    STRAHL_OP(Div) dst() = a() / b(); STRAHL_NEXT;
    STRAHL_OP(Min) dst() = num::min(a(), b()); STRAHL_NEXT;
    STRAHL_OP(Max) dst() = num::max(a(), b()); STRAHL_NEXT;
    STRAHL_OP(Powr) dst() = num::powr(a(), b()); STRAHL_NEXT;
    STRAHL_OP(AddImm) dst() = formula_detail::addImm(a(), imm()); STRAHL_NEXT;
    STRAHL_OP(MulImm) dst() = formula_detail::mulImm(a(), imm()); STRAHL_NEXT;
    STRAHL_OP(DivImm) dst() = formula_detail::divImm(a(), imm()); STRAHL_NEXT;
    STRAHL_OP(MinImm) dst() = num::min(a(), T(imm())); STRAHL_NEXT;
    STRAHL_OP(MaxImm) dst() = num::max(a(), T(imm())); STRAHL_NEXT;
    STRAHL_OP(PowiImm) dst() = num::powi(a(), static_cast<int>(imm())); STRAHL_NEXT;
    STRAHL_OP(PowrImm) dst() = num::powr(a(), imm()); STRAHL_NEXT;
    STRAHL_OP(SubImmLeft) dst() = formula_detail::subFromImm(imm(), a()); STRAHL_NEXT;
    STRAHL_OP(DivImmLeft) dst() = T(imm()) / a(); STRAHL_NEXT;
    STRAHL_OP(PowrImmLeft) dst() = num::powr(T(imm()), a()); STRAHL_NEXT;
    STRAHL_OP(Neg) dst() = -a(); STRAHL_NEXT;
    STRAHL_OP(Sqr) dst() = num::sqr(a()); STRAHL_NEXT;
    STRAHL_OP(Sqrt) dst() = num::sqrt(a()); STRAHL_NEXT;
    STRAHL_OP(Abs) dst() = num::abs(a()); STRAHL_NEXT;
    STRAHL_OP(Exp) dst() = num::exp(a()); STRAHL_NEXT;
    STRAHL_OP(Log) dst() = num::log(a()); STRAHL_NEXT;
    STRAHL_OP(Sin) dst() = num::sin(a()); STRAHL_NEXT;
    STRAHL_OP(Cos) dst() = num::cos(a()); STRAHL_NEXT;
    STRAHL_OP(Tan) dst() = num::tan(a()); STRAHL_NEXT;
    STRAHL_OP(Atan) dst() = num::atan(a()); STRAHL_NEXT;
    STRAHL_OP(SqrAddSqr) dst() = num::sqr(a()) + num::sqr(b()); STRAHL_NEXT;
    STRAHL_OP(Hypot) dst() = num::sqrt(num::sqr(a()) + num::sqr(b())); STRAHL_NEXT;
    STRAHL_OP(AddSqr) dst() = a() + num::sqr(b()); STRAHL_NEXT;
    STRAHL_OP(AddShiftedSqr)
        dst() = a() + num::sqr(formula_detail::addImm(b(), imm())); STRAHL_NEXT;
    STRAHL_OP(SqrAddImm) dst() = formula_detail::addImm(num::sqr(a()), imm()); STRAHL_NEXT;
    STRAHL_OP(MulAdd) dst() = a() * b() + c(); STRAHL_NEXT;
    STRAHL_OP(MulImmAdd) dst() = formula_detail::mulImm(a(), imm()) + b(); STRAHL_NEXT;
    // clang-format on
#if STRAHL_FORMULA_THREADED
#pragma GCC diagnostic pop
#else
        }
    }
#endif
#undef STRAHL_OP
#undef STRAHL_NEXT
}

#undef STRAHL_FORMULA_THREADED

}  // namespace strahl
