#include "core/surface/expression/formula_tape.h"

#include <muParser.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string_view>

namespace dynamesh {

namespace {

using Code = FormulaTape::Code;

// The functions muparser 2.3.3 defines by default (Parser::InitFun), with their argument
// counts (-1: any number).
struct KnownFunction {
  std::string_view name;
  Code code;
  int argc;
};

constexpr KnownFunction kKnownFunctions[] = {
    {"sin", Code::kSin, 1},     {"cos", Code::kCos, 1},     {"tan", Code::kTan, 1},
    {"asin", Code::kAsin, 1},   {"acos", Code::kAcos, 1},   {"atan", Code::kAtan, 1},
    {"atan2", Code::kAtan2, 2}, {"sinh", Code::kSinh, 1},   {"cosh", Code::kCosh, 1},
    {"tanh", Code::kTanh, 1},   {"asinh", Code::kAsinh, 1}, {"acosh", Code::kAcosh, 1},
    {"atanh", Code::kAtanh, 1}, {"log2", Code::kLog2, 1},   {"log10", Code::kLog10, 1},
    {"log", Code::kLog, 1},     {"ln", Code::kLog, 1},      {"exp", Code::kExp, 1},
    {"sqrt", Code::kSqrt, 1},   {"sign", Code::kSign, 1},   {"rint", Code::kRint, 1},
    {"abs", Code::kAbs, 1},     {"sum", Code::kSum, -1},    {"avg", Code::kAvg, -1},
    {"min", Code::kMin, -1},    {"max", Code::kMax, -1},
};

struct KnownCallback {
  mu::erased_fun_type address;
  Code code;
  int argc;  // -1: any number; 0 for unary plus, which emits nothing
};

// The first callback a one-variable formula such as "-a" calls (nullptr if none: muparser
// optimises unary plus away).
mu::erased_fun_type first_callback(const char* formula) {
  mu::Parser parser;
  double a = 0.5;
  parser.DefineVar("a", &a);
  parser.SetExpr(formula);
  parser.Eval();
  const mu::ParserByteCode& bytecode = parser.GetByteCode();
  for (std::size_t i = 0; i < bytecode.GetSize(); ++i)
    if (bytecode.GetBase()[i].Cmd == mu::cmFUNC) return bytecode.GetBase()[i].Fun.cb._pRawFun;
  return nullptr;
}

// Callbacks are recognised by address, against those of a parser with muparser's defaults
// only: a parser where someone redefined "sin" calls another address, which is then unknown
// (and not mistaken for the sine). Unary minus and plus are not listed by any public accessor
// (they are infix operators), so their addresses are read off the bytecode of "-a" and "+a".
const std::vector<KnownCallback>& known_callbacks() {
  static const std::vector<KnownCallback> callbacks = [] {
    std::vector<KnownCallback> list;
    const mu::Parser reference;
    for (const auto& [name, callback] : reference.GetFunDef()) {
      if (callback.GetUserData() != nullptr || callback.GetCode() != mu::cmFUNC) continue;
      for (const KnownFunction& f : kKnownFunctions)
        if (name == f.name && callback.GetArgc() == f.argc)
          list.push_back(
              {reinterpret_cast<mu::erased_fun_type>(callback.GetAddr()), f.code, f.argc});
    }
    if (const mu::erased_fun_type minus = first_callback("-a"))
      list.push_back({minus, Code::kNeg, 1});
    if (const mu::erased_fun_type plus = first_callback("+a"))
      list.push_back({plus, Code::kEnd, 0});
    return list;
  }();
  return callbacks;
}

const KnownCallback* find_callback(const mu::generic_callable_type& cb) {
  if (cb._pUserData != nullptr) return nullptr;
  for (const KnownCallback& known : known_callbacks())
    if (known.address == cb._pRawFun) return &known;
  return nullptr;
}

// ---------------------------------------------------------------------------------------------
// Evaluation rules. Values are written exactly as muparser 2.3.3 computes them (MathImpl):
// asinh as log(x + sqrt(x^2 + 1)), log2 as log(x) / log(2), rint as floor(x + 0.5), ...

// sin, cos, ... with their first two derivatives (only those the order needs are computed).
template <Code C, int Order>
jet::Taylor unary_taylor(double x) {
  constexpr bool d1 = Order >= 1;
  if constexpr (C == Code::kSin) {
    const double s = std::sin(x);
    return {s, d1 ? std::cos(x) : 0.0, -s};
  } else if constexpr (C == Code::kCos) {
    const double c = std::cos(x);
    return {c, d1 ? -std::sin(x) : 0.0, -c};
  } else if constexpr (C == Code::kTan) {
    const double t = std::tan(x), f1 = 1.0 + t * t;
    return {t, f1, 2.0 * t * f1};
  } else if constexpr (C == Code::kAsin) {
    const double r = d1 ? 1.0 / std::sqrt(1.0 - x * x) : 0.0;
    return {std::asin(x), r, x * r * r * r};
  } else if constexpr (C == Code::kAcos) {
    const double r = d1 ? 1.0 / std::sqrt(1.0 - x * x) : 0.0;
    return {std::acos(x), -r, -x * r * r * r};
  } else if constexpr (C == Code::kAtan) {
    const double r = 1.0 / (1.0 + x * x);
    return {std::atan(x), r, -2.0 * x * r * r};
  } else if constexpr (C == Code::kSinh) {
    const double s = std::sinh(x);
    return {s, d1 ? std::cosh(x) : 0.0, s};
  } else if constexpr (C == Code::kCosh) {
    const double c = std::cosh(x);
    return {c, d1 ? std::sinh(x) : 0.0, c};
  } else if constexpr (C == Code::kTanh) {
    const double t = std::tanh(x), f1 = 1.0 - t * t;
    return {t, f1, -2.0 * t * f1};
  } else if constexpr (C == Code::kAsinh) {
    const double r = d1 ? 1.0 / std::sqrt(x * x + 1.0) : 0.0;
    return {std::log(x + std::sqrt(x * x + 1)), r, -x * r * r * r};
  } else if constexpr (C == Code::kAcosh) {
    const double r = d1 ? 1.0 / std::sqrt(x * x - 1.0) : 0.0;
    return {std::log(x + std::sqrt(x * x - 1)), r, -x * r * r * r};
  } else if constexpr (C == Code::kAtanh) {
    const double r = 1.0 / (1.0 - x * x);
    return {0.5 * std::log((1 + x) / (1 - x)), r, 2.0 * x * r * r};
  } else if constexpr (C == Code::kLog) {
    const double r = 1.0 / x;
    return {std::log(x), r, -r * r};
  } else if constexpr (C == Code::kLog2) {
    const double r = 1.0 / (x * std::numbers::ln2);
    return {std::log(x) / std::log(2.0), r, -r / x};
  } else if constexpr (C == Code::kLog10) {
    const double r = 1.0 / (x * std::numbers::ln10);
    return {std::log10(x), r, -r / x};
  } else if constexpr (C == Code::kExp) {
    const double e = std::exp(x);
    return {e, e, e};
  } else if constexpr (C == Code::kSqrt) {
    // 1/sqrt(x) as sqrt(x) * (1/x): the root and the division run side by side instead of
    // one after the other (~20 cycles less latency on the hot path of sphere-like formulas).
    // (At 0 and infinity that product is 0 * inf: there 1/sqrt(x) is taken directly.)
    const double s = std::sqrt(x), q = d1 ? 1.0 / x : 0.0;
    const double r = (x == 0.0 || std::isinf(x)) ? 1.0 / s : s * q;
    return {s, 0.5 * r, -0.25 * r * q};
  } else if constexpr (C == Code::kSign) {
    return {(x < 0) ? -1.0 : (x > 0) ? 1.0 : 0.0, 0.0, 0.0};
  } else if constexpr (C == Code::kRint) {
    return {std::floor(x + 0.5), 0.0, 0.0};
  } else if constexpr (C == Code::kAbs) {
    // |x| at 0: the central difference 0; the kink's delta in f'' is dropped.
    return {(x >= 0) ? x : -x, (x > 0) ? 1.0 : (x < 0) ? -1.0 : 0.0, 0.0};
  } else {
    static_assert(C == Code::kAbs, "not a function of one argument");  // (never true here)
  }
}

// x^n for the muparser's VARPOW codes, as the products muparser forms.
template <class J>
void input_power(J& r, double x, int i, int n) {
  r.set_input(x, i);
  const double x2 = x * x;
  r.value = n == 2 ? x2 : n == 3 ? x2 * x : x2 * x * x;
  if constexpr (J::kGrad > 0) {
    if (i < J::kInputs) {
      r.grad[i] = n == 2 ? 2.0 * x : n == 3 ? 3.0 * x2 : 4.0 * x2 * x;
      if constexpr (J::kHess > 0)
        r.hess[J::hessian_index(i, i)] = n == 2 ? 2.0 : n == 3 ? 6.0 * x : 12.0 * x2;
    }
  }
}

// What the leaf op `code` (kConst, kVar, kVarMul, kVarPow2..4) with op's arg, a and b pushes:
// muparser's VARMUL is x * a + b, its VARPOWs are products.
template <class J>
[[gnu::always_inline]] inline void leaf_jet(J& r, Code code, const FormulaTape::Op& op,
                                            const double* x) {
  switch (code) {
    case Code::kConst:
      r.set_constant(op.a);
      return;
    case Code::kVar:
      r.set_input(x[op.arg], op.arg);
      return;
    case Code::kVarMul:
      r.set_input(x[op.arg], op.arg);
      jet::scale(r, op.a);
      r.value = x[op.arg] * op.a + op.b;
      return;
    case Code::kVarPow2:
      input_power(r, x[op.arg], op.arg, 2);
      return;
    case Code::kVarPow3:
      input_power(r, x[op.arg], op.arg, 3);
      return;
    default:
      input_power(r, x[op.arg], op.arg, 4);
      return;
  }
}

// a^p for a constant exponent p. The factors p a^(p-1) and p (p-1) a^(p-2) are products, so
// an integer exponent is differentiable for negative a too (pow of a negative base is NaN
// only for a fractional exponent, where the value is NaN as well); p = 0, 1, 2 avoid
// 0 * pow(0, negative) at a = 0.
template <class J>
void pow_constant(J& a, double p) {
  const double x = a.value, f0 = std::pow(x, p);
  if constexpr (J::kGrad == 0) {
    a.value = f0;
  } else {
    const double f1 = p == 0.0 ? 0.0 : p == 1.0 ? 1.0 : p * std::pow(x, p - 1.0);
    const double f2 = (J::kHess == 0 || p == 0.0 || p == 1.0) ? 0.0
                      : p == 2.0                              ? 2.0
                                 : p * (p - 1.0) * std::pow(x, p - 2.0);
    jet::chain(a, {f0, f1, f2});
  }
}

// a^b with both varying: f = exp(b log a) for a > 0. A negative base has a real power only at
// integer b, where log|a| gives the real part of the complex derivative; at a = 0 (0^b = 0 for
// b > 0) the exponent's terms vanish and the base's are those of a constant exponent.
template <class J>
void pow_general(J& a, const J& b) {
  if constexpr (J::kGrad == 0) {
    a.value = std::pow(a.value, b.value);
  } else {
    if (jet::is_constant(b)) {
      pow_constant(a, b.value);
      return;
    }
    const double x = a.value, y = b.value;
    if (x == 0.0) {
      pow_constant(a, y);
      return;
    }
    const double f = std::pow(x, y), L = std::log(std::abs(x)), q = std::pow(x, y - 1.0);
    jet::chain2(a, b, {f, y * q, f * L, y * (y - 1.0) * q / x, q * (1.0 + y * L), f * L * L});
  }
}

// atan2(y, x): d/dy = x / r2, d/dx = -y / r2 (r2 = x^2 + y^2); at the origin, where the angle
// has no derivative, zero.
template <class J>
void atan2_jet(J& y, const J& x) {
  const double v = std::atan2(y.value, x.value);
  if constexpr (J::kGrad == 0) {
    y.value = v;
  } else {
    const double r2 = x.value * x.value + y.value * y.value;
    if (r2 == 0.0) {
      y.set_constant(v);
      return;
    }
    const double xy = x.value * y.value, r4 = r2 * r2;
    jet::chain2(y, x,
                {v, x.value / r2, -y.value / r2, -2.0 * xy / r4,
                 (y.value * y.value - x.value * x.value) / r4, 2.0 * xy / r4});
  }
}

// min / max of n entries at s[0..n): muparser keeps the first extreme (std::min / std::max in
// order, so a NaN counts only in first place). Where several arguments tie, the derivatives
// are their average: what central differences see where two arguments cross.
template <class J, bool kMax>
void extreme(J* s, int n) {
  double m = s[0].value;
  for (int i = 0; i < n; ++i) m = kMax ? std::max(m, s[i].value) : std::min(m, s[i].value);
  if constexpr (J::kGrad > 0) {
    int first = 0;
    while (first < n && !(s[first].value == m)) ++first;
    if (first == n) return;  // m is NaN: s[0] is the result
    J r = s[first];
    int ties = 1;
    for (int i = first + 1; i < n; ++i)
      if (s[i].value == m) {
        jet::add(r, s[i]);
        ++ties;
      }
    if (ties > 1) jet::scale(r, 1.0 / ties);
    r.value = m;
    s[0] = r;
  } else {
    s[0].value = m;
  }
}

// ---------------------------------------------------------------------------------------------
// Rewriting tapes: fusing leaves into the op that consumes them, and folding constants.

using Op = FormulaTape::Op;

bool is_leaf(Code code) {
  return code >= Code::kConst && code <= Code::kVarPow4;
}
bool is_jump(Code code) {
  return code == Code::kIf || code == Code::kJump;
}

// Stack entries an op consumes; -1 for control flow (never folded).
int operand_count(const Op& op) {
  switch (op.code) {
    case Code::kConst:
    case Code::kVar:
    case Code::kVarMul:
    case Code::kVarPow2:
    case Code::kVarPow3:
    case Code::kVarPow4:
      return 0;
    case Code::kIf:
    case Code::kJump:
    case Code::kEnd:
      return -1;
    case Code::kSum:
    case Code::kAvg:
    case Code::kMin:
    case Code::kMax:
      return op.arg;
    case Code::kPowConst:
    case Code::kNeg:
    case Code::kAddLeaf:
    case Code::kSubLeaf:
    case Code::kMulLeaf:
    case Code::kDivLeaf:
      return 1;
    default:
      return op.code >= Code::kSin && op.code <= Code::kAbs ? 1 : 2;
  }
}

// Rewrites a tape op by op: step(k, k_is_target, out, out_target) appends what op k becomes
// to `out`. It may also take back ops it appended before, to merge them with op k, but never
// across a jump target (control may arrive there with other entries on the stack):
// out_target[i] tells whether out[i] is jumped to. Jumps are then redirected to the first op
// made for their old target.
template <class Step>
std::vector<Op> rewrite(const std::vector<Op>& ops, Step&& step) {
  std::vector<bool> is_target(ops.size() + 1, false);
  for (const Op& op : ops)
    if (is_jump(op.code)) is_target[static_cast<std::size_t>(op.arg)] = true;
  std::vector<Op> out;
  std::vector<bool> out_target;
  std::vector<int> new_index(ops.size() + 1, 0);
  for (std::size_t k = 0; k < ops.size(); ++k) {
    const std::size_t before = out.size();
    step(k, is_target[k], out, out_target);
    // A merge may have replaced ops before this one: this op now starts where it stopped.
    new_index[k] = static_cast<int>(std::min(before, out.size()));
    out_target.resize(out.size(), false);
    if (out.size() > before && is_target[k]) out_target[before] = true;
  }
  new_index[ops.size()] = static_cast<int>(out.size());
  for (Op& op : out)
    if (is_jump(op.code)) op.arg = new_index[static_cast<std::size_t>(op.arg)];
  return out;
}

Code fused_code(Code binary) {
  switch (binary) {
    case Code::kAdd:
      return Code::kAddLeaf;
    case Code::kSub:
      return Code::kSubLeaf;
    case Code::kMul:
      return Code::kMulLeaf;
    case Code::kDiv:
      return Code::kDivLeaf;
    default:
      return Code::kEnd;
  }
}

Code binary_code(Code fused) {
  switch (fused) {
    case Code::kAddLeaf:
      return Code::kAdd;
    case Code::kSubLeaf:
      return Code::kSub;
    case Code::kMulLeaf:
      return Code::kMul;
    case Code::kDivLeaf:
      return Code::kDiv;
    default:
      return Code::kEnd;
  }
}

// "leaf; + - * /" -> one k*Leaf op (unless the operator is jumped to).
std::vector<Op> fuse_leaves(const std::vector<Op>& ops) {
  return rewrite(ops,
                 [&](std::size_t k, bool target, std::vector<Op>& out, const std::vector<bool>&) {
                   const Op& op = ops[k];
                   const Code fused = fused_code(op.code);
                   if (fused != Code::kEnd && !target && !out.empty() && is_leaf(out.back().code)) {
                     Op& leaf = out.back();
                     leaf.leaf = leaf.code;
                     leaf.code = fused;
                     return;
                   }
                   out.push_back(op);
                 });
}

std::vector<Op> split_leaves(const std::vector<Op>& ops) {
  return rewrite(ops, [&](std::size_t k, bool, std::vector<Op>& out, const std::vector<bool>&) {
    Op op = ops[k];
    const Code binary = binary_code(op.code);
    if (binary == Code::kEnd) {
      out.push_back(op);
      return;
    }
    op.code = op.leaf;
    op.leaf = Code::kEnd;
    out.push_back(op);
    out.push_back({binary});
  });
}

}  // namespace

std::optional<FormulaTape> FormulaTape::translate(const mu::Parser& parser,
                                                  std::span<double* const> inputs) {
  if (inputs.size() > kMaxInputs) return std::nullopt;
  const mu::ParserByteCode& bytecode = parser.GetByteCode();
  if (bytecode.GetSize() == 0) return std::nullopt;
  const mu::SToken* tokens = bytecode.GetBase();
  const int n = static_cast<int>(bytecode.GetSize());

  // muparser jumps: after "if" at k (condition 0) or "else" at k, the next token run is
  // k + offset + 1 (ParseCmdCodeBulk adds the offset, then the loop's increment).
  std::vector<bool> is_target(n + 1, false);
  for (int k = 0; k < n; ++k)
    if (tokens[k].Cmd == mu::cmIF || tokens[k].Cmd == mu::cmELSE) {
      const int target = k + tokens[k].Oprt.offset + 1;
      if (target <= k || target > n) return std::nullopt;
      is_target[target] = true;
    }

  FormulaTape tape;
  tape.inputs_ = static_cast<int>(inputs.size());
  std::vector<int> first_op(n + 1, 0);  // muparser token -> first op emitted for it
  std::vector<int> jump_sources;        // ops whose arg is still a muparser token index
  int depth = 0;
  std::vector<int> branch_depths;  // per open "?:", the depth its branches must end at
  auto emit = [&](Code code, int pops, int pushes, int arg = 0, double a = 0.0, double b = 0.0) {
    if (depth < pops) return false;
    depth += pushes - pops;
    tape.max_depth_ = std::max(tape.max_depth_, depth);
    tape.ops_.push_back({code, arg, a, b});
    return true;
  };
  auto input_of = [&](const double* address) {
    for (std::size_t i = 0; i < inputs.size(); ++i)
      if (inputs[i] == address) return static_cast<int>(i);
    return -1;
  };

  bool ended = false;
  for (int k = 0; k < n && !ended; ++k) {
    first_op[k] = static_cast<int>(tape.ops_.size());
    const mu::SToken& t = tokens[k];
    bool ok = true;
    switch (t.Cmd) {
      case mu::cmVAL:
        // "push p; pow" is a power with a constant exponent (unless a jump lands between).
        if (k + 1 < n && tokens[k + 1].Cmd == mu::cmPOW && !is_target[k + 1]) {
          ok = emit(Code::kPowConst, 1, 1, 0, t.Val.data2);
          first_op[k + 1] = first_op[k];
          ++k;
        } else {
          ok = emit(Code::kConst, 0, 1, 0, t.Val.data2);
        }
        break;
      case mu::cmVAR:
      case mu::cmVARMUL:
      case mu::cmVARPOW2:
      case mu::cmVARPOW3:
      case mu::cmVARPOW4: {
        const int i = input_of(t.Val.ptr);
        if (i < 0) return std::nullopt;
        const Code code = t.Cmd == mu::cmVAR       ? Code::kVar
                          : t.Cmd == mu::cmVARMUL  ? Code::kVarMul
                          : t.Cmd == mu::cmVARPOW2 ? Code::kVarPow2
                          : t.Cmd == mu::cmVARPOW3 ? Code::kVarPow3
                                                   : Code::kVarPow4;
        ok = emit(code, 0, 1, i, t.Val.data, t.Val.data2);
        break;
      }
      case mu::cmLE:
        ok = emit(Code::kLe, 2, 1);
        break;
      case mu::cmGE:
        ok = emit(Code::kGe, 2, 1);
        break;
      case mu::cmNEQ:
        ok = emit(Code::kNe, 2, 1);
        break;
      case mu::cmEQ:
        ok = emit(Code::kEq, 2, 1);
        break;
      case mu::cmLT:
        ok = emit(Code::kLt, 2, 1);
        break;
      case mu::cmGT:
        ok = emit(Code::kGt, 2, 1);
        break;
      case mu::cmADD:
        ok = emit(Code::kAdd, 2, 1);
        break;
      case mu::cmSUB:
        ok = emit(Code::kSub, 2, 1);
        break;
      case mu::cmMUL:
        ok = emit(Code::kMul, 2, 1);
        break;
      case mu::cmDIV:
        ok = emit(Code::kDiv, 2, 1);
        break;
      case mu::cmPOW:
        ok = emit(Code::kPow, 2, 1);
        break;
      case mu::cmLAND:
        ok = emit(Code::kAnd, 2, 1);
        break;
      case mu::cmLOR:
        ok = emit(Code::kOr, 2, 1);
        break;
      case mu::cmIF:
        jump_sources.push_back(static_cast<int>(tape.ops_.size()));
        ok = emit(Code::kIf, 1, 0, k + t.Oprt.offset + 1);
        branch_depths.push_back(depth);
        break;
      case mu::cmELSE:
        // The "then" branch ends here with one more entry; the "else" branch starts again
        // from the depth after the condition was popped and must end at the same depth.
        if (branch_depths.empty() || depth != branch_depths.back() + 1) return std::nullopt;
        jump_sources.push_back(static_cast<int>(tape.ops_.size()));
        ok = emit(Code::kJump, 0, 0, k + t.Oprt.offset + 1);
        std::swap(depth, branch_depths.back());
        break;
      case mu::cmENDIF:
        if (branch_depths.empty() || depth != branch_depths.back()) return std::nullopt;
        branch_depths.pop_back();
        break;
      case mu::cmFUNC: {
        const KnownCallback* f = find_callback(t.Fun.cb);
        if (f == nullptr) return std::nullopt;
        if (f->argc == 0) {  // unary plus: the identity
          ok = t.Fun.argc == 1 && depth >= 1;
        } else if (f->argc > 0) {
          ok = t.Fun.argc == f->argc && emit(f->code, f->argc, 1);
        } else {
          const int args = -t.Fun.argc;
          ok = args >= 1 && emit(f->code, args, 1, args);
        }
        break;
      }
      case mu::cmEND:
        ok = emit(Code::kEnd, 0, 0);
        ended = true;
        break;
      default:  // strings, bulk functions, assignments, anything newer
        return std::nullopt;
    }
    if (!ok) return std::nullopt;
  }
  first_op[n] = static_cast<int>(tape.ops_.size());
  if (!ended || !branch_depths.empty() || depth != parser.GetNumResults() || depth < 1)
    return std::nullopt;
  for (const int j : jump_sources) tape.ops_[j].arg = first_op[tape.ops_[j].arg];
  tape.ops_ = fuse_leaves(tape.ops_);
  tape.outputs_ = depth;
  return tape;
}

FormulaTape FormulaTape::bind(int input, double value) const {
  FormulaTape bound;
  bound.inputs_ = inputs_;
  bound.outputs_ = outputs_;
  bound.max_depth_ = max_depth_;  // folding only lowers the depth
  std::vector<double> x(static_cast<std::size_t>(inputs_), 0.0);
  if (input >= 0 && input < inputs_) x[static_cast<std::size_t>(input)] = value;
  const std::vector<Op> plain = split_leaves(ops_);
  const std::vector<Op> folded = rewrite(
      plain,
      [&](std::size_t k, bool target, std::vector<Op>& out, const std::vector<bool>& out_target) {
        const Op& op = plain[k];
        const int n = operand_count(op);
        const std::size_t size = out.size();
        // Fold when the op's operands are all constants pushed right before it (in straight-line
        // code), or when it pushes the bound input.
        bool fold = n == 0 && op.code != Code::kConst && op.arg == input;
        if (n > 0 && !target && size >= static_cast<std::size_t>(n)) {
          fold = true;
          for (std::size_t j = size - n; j < size; ++j)
            fold = fold && out[j].code == Code::kConst && (j == size - n || !out_target[j]);
        }
        if (!fold) {
          out.push_back(op);
          return;
        }
        // Run the op on its constant operands, as evaluation would, and keep the result.
        FormulaTape single;
        single.inputs_ = inputs_;
        single.outputs_ = 1;
        single.max_depth_ = std::max(n, 1);
        single.ops_.assign(out.end() - n, out.end());
        single.ops_.push_back(op);
        single.ops_.push_back({Code::kEnd});
        ForwardJet<0, 0> result;
        single.evaluate<0, 0>(x, std::span(&result, 1));
        out.resize(size - n);
        out.push_back({Code::kConst, 0, result.value});
      });
  bound.ops_ = fuse_leaves(folded);
  return bound;
}

template <class J>
void FormulaTape::run(const double* x, J* s) const {
  constexpr int kOrder = J::kOrder;
  int sp = -1;
  for (int pc = 0;;) {
    const Op& op = ops_[pc++];
    // Every op but the functions of one argument is done inside the switch and continues the
    // loop; those functions only give their Taylor coefficients, and the one chain rule after
    // the switch applies them (one copy of it, inlined, instead of one call per function).
    jet::Taylor t;
    switch (op.code) {
      case Code::kConst:
        s[++sp].set_constant(op.a);
        continue;
      case Code::kVar:
        s[++sp].set_input(x[op.arg], op.arg);
        continue;
      case Code::kVarMul:
      case Code::kVarPow2:
      case Code::kVarPow3:
      case Code::kVarPow4:
        leaf_jet(s[++sp], op.code, op, x);
        continue;
      // Fused "leaf; op". A constant leaf leaves the derivatives alone (+, -) or scales them
      // (*, /); the value is computed as the unfused op would.
      case Code::kAddLeaf:
        if (op.leaf == Code::kConst) {
          s[sp].value += op.a;
        } else {
          J r;
          leaf_jet(r, op.leaf, op, x);
          jet::add(s[sp], r);
        }
        continue;
      case Code::kSubLeaf:
        if (op.leaf == Code::kConst) {
          s[sp].value -= op.a;
        } else {
          J r;
          leaf_jet(r, op.leaf, op, x);
          jet::sub(s[sp], r);
        }
        continue;
      case Code::kMulLeaf:
        if (op.leaf == Code::kConst) {
          jet::scale(s[sp], op.a);
        } else {
          J r;
          leaf_jet(r, op.leaf, op, x);
          jet::mul(s[sp], r);
        }
        continue;
      case Code::kDivLeaf:
        if (op.leaf == Code::kConst) {
          jet::divide(s[sp], op.a);
        } else {
          J r;
          leaf_jet(r, op.leaf, op, x);
          jet::div(s[sp], r);
        }
        continue;
      case Code::kAdd:
        --sp;
        jet::add(s[sp], s[sp + 1]);
        continue;
      case Code::kSub:
        --sp;
        jet::sub(s[sp], s[sp + 1]);
        continue;
      case Code::kMul:
        --sp;
        jet::mul(s[sp], s[sp + 1]);
        continue;
      case Code::kDiv:
        --sp;
        jet::div(s[sp], s[sp + 1]);
        continue;
      case Code::kPow:
        --sp;
        pow_general(s[sp], s[sp + 1]);
        continue;
      case Code::kPowConst:
        pow_constant(s[sp], op.a);
        continue;
      // Comparisons and logic: piecewise constant, so no derivatives (muparser: 1 or 0; a
      // NaN operand is "true" for && and ||, as in C++).
      case Code::kLe:
        --sp;
        s[sp].set_constant(s[sp].value <= s[sp + 1].value);
        continue;
      case Code::kGe:
        --sp;
        s[sp].set_constant(s[sp].value >= s[sp + 1].value);
        continue;
      case Code::kNe:
        --sp;
        s[sp].set_constant(s[sp].value != s[sp + 1].value);
        continue;
      case Code::kEq:
        --sp;
        s[sp].set_constant(s[sp].value == s[sp + 1].value);
        continue;
      case Code::kLt:
        --sp;
        s[sp].set_constant(s[sp].value < s[sp + 1].value);
        continue;
      case Code::kGt:
        --sp;
        s[sp].set_constant(s[sp].value > s[sp + 1].value);
        continue;
      case Code::kAnd:
        --sp;
        s[sp].set_constant(s[sp].value != 0.0 && s[sp + 1].value != 0.0);
        continue;
      case Code::kOr:
        --sp;
        s[sp].set_constant(s[sp].value != 0.0 || s[sp + 1].value != 0.0);
        continue;
      // "c ? a : b": only the taken branch runs, so its derivatives are the result's.
      case Code::kIf:
        if (s[sp--].value == 0.0) pc = op.arg;
        continue;
      case Code::kJump:
        pc = op.arg;
        continue;
      case Code::kNeg:
        jet::negate(s[sp]);
        continue;
      case Code::kAtan2:
        --sp;
        atan2_jet(s[sp], s[sp + 1]);
        continue;
      case Code::kSum:
      case Code::kAvg: {
        const int n = op.arg;
        sp -= n - 1;
        double sum = 0.0;  // muparser starts from 0 (so -0 + ... gives +0, as there)
        for (int i = 0; i < n; ++i) sum += s[sp + i].value;
        for (int i = 1; i < n; ++i) jet::add(s[sp], s[sp + i]);
        if (op.code == Code::kAvg) {
          jet::scale(s[sp], 1.0 / n);
          sum /= n;
        }
        s[sp].value = sum;
        continue;
      }
      case Code::kMin:
        sp -= op.arg - 1;
        extreme<J, false>(s + sp, op.arg);
        continue;
      case Code::kMax:
        sp -= op.arg - 1;
        extreme<J, true>(s + sp, op.arg);
        continue;
      case Code::kEnd:
        return;
      case Code::kSin:
        t = unary_taylor<Code::kSin, kOrder>(s[sp].value);
        break;
      case Code::kCos:
        t = unary_taylor<Code::kCos, kOrder>(s[sp].value);
        break;
      case Code::kTan:
        t = unary_taylor<Code::kTan, kOrder>(s[sp].value);
        break;
      case Code::kAsin:
        t = unary_taylor<Code::kAsin, kOrder>(s[sp].value);
        break;
      case Code::kAcos:
        t = unary_taylor<Code::kAcos, kOrder>(s[sp].value);
        break;
      case Code::kAtan:
        t = unary_taylor<Code::kAtan, kOrder>(s[sp].value);
        break;
      case Code::kSinh:
        t = unary_taylor<Code::kSinh, kOrder>(s[sp].value);
        break;
      case Code::kCosh:
        t = unary_taylor<Code::kCosh, kOrder>(s[sp].value);
        break;
      case Code::kTanh:
        t = unary_taylor<Code::kTanh, kOrder>(s[sp].value);
        break;
      case Code::kAsinh:
        t = unary_taylor<Code::kAsinh, kOrder>(s[sp].value);
        break;
      case Code::kAcosh:
        t = unary_taylor<Code::kAcosh, kOrder>(s[sp].value);
        break;
      case Code::kAtanh:
        t = unary_taylor<Code::kAtanh, kOrder>(s[sp].value);
        break;
      case Code::kLog:
        t = unary_taylor<Code::kLog, kOrder>(s[sp].value);
        break;
      case Code::kLog2:
        t = unary_taylor<Code::kLog2, kOrder>(s[sp].value);
        break;
      case Code::kLog10:
        t = unary_taylor<Code::kLog10, kOrder>(s[sp].value);
        break;
      case Code::kExp:
        t = unary_taylor<Code::kExp, kOrder>(s[sp].value);
        break;
      case Code::kSqrt:
        t = unary_taylor<Code::kSqrt, kOrder>(s[sp].value);
        break;
      case Code::kSign:
        t = unary_taylor<Code::kSign, kOrder>(s[sp].value);
        break;
      case Code::kRint:
        t = unary_taylor<Code::kRint, kOrder>(s[sp].value);
        break;
      case Code::kAbs:
        t = unary_taylor<Code::kAbs, kOrder>(s[sp].value);
        break;
    }
    jet::chain(s[sp], t);
  }
}

template <int N, int Order>
void FormulaTape::evaluate(std::span<const double> inputs,
                           std::span<ForwardJet<N, Order>> out) const {
  using J = ForwardJet<N, Order>;
  const double* in = inputs.data();
  double padded[kMaxInputs];
  if (inputs.size() < static_cast<std::size_t>(inputs_)) {  // inputs not given read as 0
    std::fill(std::copy(inputs.begin(), inputs.end(), padded), padded + kMaxInputs, 0.0);
    in = padded;
  }
  if (out.size() >= static_cast<std::size_t>(max_depth_)) {
    run(in, out.data());
    return;
  }
  J local[kLocalStack];
  J* stack = local;
  if (max_depth_ > kLocalStack) {
    thread_local std::vector<J> deep;
    if (deep.size() < static_cast<std::size_t>(max_depth_)) deep.resize(max_depth_);
    stack = deep.data();
  }
  run(in, stack);
  std::copy_n(stack, outputs_, out.begin());
}

template void FormulaTape::evaluate<0, 0>(std::span<const double>,
                                          std::span<ForwardJet<0, 0>>) const;
template void FormulaTape::evaluate<2, 1>(std::span<const double>,
                                          std::span<ForwardJet<2, 1>>) const;
template void FormulaTape::evaluate<2, 2>(std::span<const double>,
                                          std::span<ForwardJet<2, 2>>) const;
template void FormulaTape::evaluate<3, 1>(std::span<const double>,
                                          std::span<ForwardJet<3, 1>>) const;
template void FormulaTape::evaluate<3, 2>(std::span<const double>,
                                          std::span<ForwardJet<3, 2>>) const;

}  // namespace dynamesh
