// FormulaTape: a parsed formula as a small program of our own, evaluated on jets
// (forward_jet.h) to give exact first and second derivatives.
//
// muparser parses a formula into bytecode in reverse Polish notation (ParserByteCode): pushes
// of constants and variables, built-in operators, calls of callbacks and jumps for "a ? b : c".
// translate() reads that bytecode once and rewrites it as a vector of TapeOps that name what
// each step computes (sin, +, a jump to op 12 ...) instead of pointing at muparser's callbacks
// and variables, so that the tape
//  - evaluates on any number type: values, or jets carrying derivatives, by the rule of each
//    operation (muparser can only run its callbacks on doubles);
//  - reads its inputs from the caller's array and keeps its stack on the caller's stack, so
//    one tape serves every thread at once, with no per-thread parser, lock or allocation.
// Values are computed with the same operations in the same order as muparser 2.3.3
// (MathImpl in muParserTemplateMagic.h), so they agree with muparser's to the last bit.
//
// A callback translate() does not know (a function defined by a user of the parser, a string
// or bulk function, an assignment "x = ...") makes it give up: the caller then keeps muparser
// and finite differences for that formula, never a wrong derivative.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "core/surface/expression/forward_jet.h"

namespace mu {
class Parser;
}

namespace dynamesh {

class FormulaTape {
 public:
  enum class Code : std::uint8_t {
    kConst,    // push a
    kVar,      // push input[arg]
    kVarMul,   // push input[arg] * a + b
    kVarPow2,  // push input[arg]^2, ^3, ^4 (as products)
    kVarPow3,
    kVarPow4,
    kAdd,
    kSub,
    kMul,
    kDiv,
    kPow,       // top-1 ^ top
    kPowConst,  // top ^ a (muparser's "push a; pow", fused)
    kLe,
    kGe,
    kNe,
    kEq,
    kLt,
    kGt,
    kAnd,
    kOr,
    kIf,    // pop; jump to op arg when it is 0
    kJump,  // jump to op arg (the end of a taken "then" branch)
    kNeg,
    kSin,
    kCos,
    kTan,
    kAsin,
    kAcos,
    kAtan,
    kSinh,
    kCosh,
    kTanh,
    kAsinh,
    kAcosh,
    kAtanh,
    kLog,
    kLog2,
    kLog10,
    kExp,
    kSqrt,
    kSign,
    kRint,
    kAbs,
    kAtan2,  // atan2(top-1, top)
    kSum,    // the top arg entries
    kAvg,
    kMin,
    kMax,
    // top = top (op) leaf, where the leaf is what a kConst, kVar, kVarMul or kVarPow op with
    // this op's arg, a and b would push: "push; op" fused into one step, which saves a
    // dispatch and a round trip of a jet through the stack ("x^2 + y^2": three steps, not 5)
    kAddLeaf,
    kSubLeaf,
    kMulLeaf,
    kDivLeaf,
    kEnd,
  };

  struct Op {
    Code code;
    int arg = 0;  // input index, jump target or argument count
    double a = 0.0, b = 0.0;
    Code leaf = Code::kEnd;  // the k*Leaf ops' leaf: kConst, kVar, kVarMul, kVarPow2..4
  };

  // The tape of `parser`'s current formula, which must have been evaluated once (muparser
  // parses on first evaluation), with its variables defined at `inputs` (input i is
  // *inputs[i]). nullopt when the bytecode holds anything not listed in Code.
  static std::optional<FormulaTape> translate(const mu::Parser& parser,
                                              std::span<double* const> inputs);

  // This tape with input `input` fixed at `value` (it still takes that input, and ignores it),
  // and every step that then depends on constants only done once, here: what a surface does
  // with the time at each set_time(), so that "0.6*(9/0.6)^t" costs one constant per
  // evaluation, not a pow. Results are those of the full tape, bit for bit (the same
  // operations in the same order, only earlier).
  FormulaTape bind(int input, double value) const;

  // Every formula's jet at `inputs` (the values of the parser's variables, in translate()'s
  // order), differentiated with respect to inputs 0..N-1; out[0..outputs()) receives them.
  // `out` holds at least outputs() jets; with max_depth() or more (kLocalStack is enough for
  // any formula but a very deep one) it also serves as the evaluation stack, which saves
  // copying the results out of another one (a copy that stalled on the stores just made).
  // Thread-safe (the tape is read-only); allocation-free, except that a formula deeper than
  // kLocalStack gets a scratch stack allocated once per thread.
  template <int N, int Order>
  void evaluate(std::span<const double> inputs, std::span<ForwardJet<N, Order>> out) const;

  int outputs() const { return outputs_; }
  int inputs() const { return inputs_; }
  int max_depth() const { return max_depth_; }
  const std::vector<Op>& ops() const { return ops_; }

  static constexpr int kLocalStack = 32;
  static constexpr std::size_t kMaxInputs = 16;

 private:
  template <class J>
  void run(const double* inputs, J* stack) const;

  std::vector<Op> ops_;
  int outputs_ = 0;
  int inputs_ = 0;
  int max_depth_ = 0;
};

// Instantiated in formula_tape.cpp: values only, and the orders the surfaces use.
extern template void FormulaTape::evaluate<0, 0>(std::span<const double>,
                                                 std::span<ForwardJet<0, 0>>) const;
extern template void FormulaTape::evaluate<2, 1>(std::span<const double>,
                                                 std::span<ForwardJet<2, 1>>) const;
extern template void FormulaTape::evaluate<2, 2>(std::span<const double>,
                                                 std::span<ForwardJet<2, 2>>) const;
extern template void FormulaTape::evaluate<3, 1>(std::span<const double>,
                                                 std::span<ForwardJet<3, 1>>) const;
extern template void FormulaTape::evaluate<3, 2>(std::span<const double>,
                                                 std::span<ForwardJet<3, 2>>) const;

}  // namespace dynamesh
