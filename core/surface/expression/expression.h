// Expression: formulas a user types (e.g. "x^2 + y^2 + z^2 - 1"), parsed once by muparser and
// evaluated many times, from many threads at once.
//
// muparser's Parser keeps its evaluation stack and its variables' storage inside the object, so
// one Parser cannot serve two threads. Each thread therefore gets its own parser for each
// Expression, built on first use in that thread and cached (keyed by a serial number that is
// never reused, so a destroyed Expression's entry can never be mistaken for a new one).
// Steady-state evaluation is a cache lookup, a copy of the inputs and muparser's bytecode
// interpreter: no allocation, no lock. (Only for formulas without a tape, see below.)
//
// One Expression may hold several formulas over the same variables (e.g. the X; Y; Z of a
// parametric surface): they are evaluated together in one pass of the interpreter.
//
// The tape: the parsed formulas are also translated once into a FormulaTape (formula_tape.h),
// which evaluates them with muparser's results, bit for bit, from any number of threads
// without a parser, and on jets, with exact derivatives. evaluate() and value() use it (it is
// faster than a parser-cache lookup and muparser's interpreter: 8 ns against 19 for "x*y+z",
// 28 against 39 for a sphere). A formula the translator does not know (see differentiable())
// has no tape: it is evaluated by the per-thread parsers above, and its users fall back to
// finite differences for derivatives.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/surface/expression/formula_tape.h"

namespace dynamesh {

class Expression {
 public:
  // `formulas`: one or more formulas in `variables` (at most kMaxVariables names), the usual
  // functions (sin, cos, tan, asin, acos, atan, sinh, cosh, tanh, exp, log, ln, log2, log10,
  // sqrt, abs, sign, rint, min, max, sum, avg), operators + - * / ^, comparisons, "a ? b : c",
  // and the constants pi and e. `role` names the formulas in error messages (e.g. "implicit
  // formula"). Throws std::invalid_argument, one line naming the formula and what is wrong,
  // for a syntax error or a name that is neither a variable, a constant nor a function.
  Expression(std::vector<std::string> formulas, std::vector<std::string> variables,
             std::string role);
  ~Expression();
  Expression(const Expression&) = delete;
  Expression& operator=(const Expression&) = delete;

  static constexpr int kMaxVariables = 8;

  std::size_t size() const { return formulas_.size(); }
  const std::vector<std::string>& formulas() const { return formulas_; }
  const std::vector<std::string>& variables() const { return variables_; }

  // Evaluates every formula with variables()[i] = values[i]; out receives size() results.
  // Thread-safe; allocation-free once the calling thread has evaluated this expression before.
  void evaluate(std::span<const double> values, std::span<double> out) const;
  // The first formula's value.
  double value(std::span<const double> values) const;

  // Comma-separated variable names, "x, y, z, t", for messages.
  std::string variable_list() const;

  // True when every formula was translated to a tape, so exact derivatives are available.
  bool differentiable() const { return tape_ != nullptr; }
  // The tape of all formulas, inputs in the order of variables(); nullptr unless
  // differentiable().
  const FormulaTape* tape() const { return tape_.get(); }
  // The tape with `variable` fixed at `value` (FormulaTape::bind), e.g. the time at each
  // set_time() of a surface; nullopt unless differentiable().
  std::optional<FormulaTape> tape_with(std::string_view variable, double value) const;

 private:
  struct Instance;
  Instance& local_instance() const;

  std::vector<std::string> formulas_;
  std::vector<std::string> variables_;
  std::string role_;
  std::string joined_;  // the formulas as one muparser expression, "(f1),(f2),..."
  std::uint64_t serial_;
  std::unique_ptr<const FormulaTape> tape_;
};

}  // namespace dynamesh
