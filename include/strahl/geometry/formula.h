#pragma once
// Formula: user-written math from scene files, such as the implicit torus
// "(x^2 + y^2 + z^2 + R^2 - r^2)^2 - 4*R^2*(x^2 + y^2)". It is parsed once and
// then evaluated millions of times per frame in double, interval and dual
// arithmetic. Syntax reference for users: docs/formulas.md.
//
// The tape: compile() turns the text into a flat list of instructions
// `dst = op(a, b, imm)` over a small array of registers. The inputs occupy the
// first registers. Constant subexpressions are folded and end up as the
// immediate of a fused instruction (2*pi*x is one MulImm), a subexpression
// written twice is computed once, and a register is reused as soon as its value
// is dead, so the working set stays small. evaluate<T>() runs the tape with one
// switch per instruction over a local array of kMaxRegisters values: no
// allocation, no recursion and no virtual calls, so one compiled formula serves
// every arithmetic at close to the speed of the same function written in C++.

#include <cstddef>
#include <cstdint>
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
    // functions, + - * / and an implicit conversion from double.
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
    uint16_t result_ = 0;  // register holding the value after the tape ran
};

// ---- the evaluator --------------------------------------------------------

namespace formula_detail {

// `dst = ...` for every instruction; registers are a and b, the constant
// operand is imm. "Left" means the immediate is the left operand.
enum class Op : uint8_t {
    Const,  // imm (only when the whole formula is constant)
    Add, Sub, Mul, Div, Min, Max, Powr,             // a op b
    AddImm, MulImm, DivImm, MinImm, MaxImm,         // a op imm (a - c is AddImm -c)
    PowiImm, PowrImm,                               // a ^ imm, integer or real exponent
    SubImmLeft, DivImmLeft, PowrImmLeft,            // imm op a
    Neg, Sqr, Sqrt, Abs, Exp, Log, Sin, Cos, Tan, Atan,  // f(a)
};

struct Instruction {
    Op op;
    uint16_t dst, a, b;
    double imm;  // the constant operand; an integer for PowiImm
};

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
// uninitialised (zeroing 64 duals would cost more than a small formula): the
// compiler guarantees that every register is written before it is read.
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

inline size_t Formula::instructionCount() const { return tape_.size(); }

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
    for (const formula_detail::Instruction& in : tape_) {
        const T& a = regs[in.a];
        // dst may be a or b: every case computes its value before assigning it.
        T& dst = regs[in.dst];
        switch (in.op) {
            case Op::Const: dst = T(in.imm); break;
            case Op::Add: dst = a + regs[in.b]; break;
            case Op::Sub: dst = a - regs[in.b]; break;
            case Op::Mul: dst = a * regs[in.b]; break;
            case Op::Div: dst = a / regs[in.b]; break;
            case Op::Min: dst = num::min(a, regs[in.b]); break;
            case Op::Max: dst = num::max(a, regs[in.b]); break;
            case Op::Powr: dst = num::powr(a, regs[in.b]); break;
            case Op::AddImm: dst = formula_detail::addImm(a, in.imm); break;
            case Op::MulImm: dst = formula_detail::mulImm(a, in.imm); break;
            case Op::DivImm: dst = formula_detail::divImm(a, in.imm); break;
            case Op::MinImm: dst = num::min(a, T(in.imm)); break;
            case Op::MaxImm: dst = num::max(a, T(in.imm)); break;
            case Op::PowiImm: dst = num::powi(a, static_cast<int>(in.imm)); break;
            case Op::PowrImm: dst = num::powr(a, in.imm); break;
            case Op::SubImmLeft: dst = formula_detail::subFromImm(in.imm, a); break;
            case Op::DivImmLeft: dst = T(in.imm) / a; break;
            case Op::PowrImmLeft: dst = num::powr(T(in.imm), a); break;
            case Op::Neg: dst = -a; break;
            case Op::Sqr: dst = num::sqr(a); break;
            case Op::Sqrt: dst = num::sqrt(a); break;
            case Op::Abs: dst = num::abs(a); break;
            case Op::Exp: dst = num::exp(a); break;
            case Op::Log: dst = num::log(a); break;
            case Op::Sin: dst = num::sin(a); break;
            case Op::Cos: dst = num::cos(a); break;
            case Op::Tan: dst = num::tan(a); break;
            case Op::Atan: dst = num::atan(a); break;
        }
    }
    return regs[result_];
}

}  // namespace strahl
