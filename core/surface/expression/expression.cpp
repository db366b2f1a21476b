#include "core/surface/expression/expression.h"

#include <muParser.h>

#include <algorithm>
#include <atomic>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <utility>

namespace dynamesh {

namespace {

std::atomic<std::uint64_t> next_serial{1};

// Bounded per-thread cache: a thread that saw many expressions come and go (the viewer
// re-typing a formula) keeps at most this many parsers.
constexpr std::size_t kThreadCacheSize = 32;

void define_names(mu::Parser& parser, const std::vector<std::string>& variables, double* storage) {
  parser.DefineConst("pi", std::numbers::pi);
  parser.DefineConst("e", std::numbers::e);
  for (std::size_t i = 0; i < variables.size(); ++i) parser.DefineVar(variables[i], &storage[i]);
}

// 'text' on one line. (Built with append: GCC 12 warns falsely, -Wrestrict, on "'" + s.)
std::string quoted_line(const std::string& text) {
  std::string out;
  out.reserve(text.size() + 2);
  out.push_back('\'');
  for (char c : text) out.push_back(c == '\n' ? ' ' : c);
  out.push_back('\'');
  return out;
}

std::string one_line(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  return text;
}

}  // namespace

struct Expression::Instance {
  double storage[kMaxVariables] = {};
  mu::Parser parser;
};

Expression::Expression(std::vector<std::string> formulas, std::vector<std::string> variables,
                       std::string role)
    : formulas_(std::move(formulas)),
      variables_(std::move(variables)),
      role_(std::move(role)),
      serial_(next_serial.fetch_add(1)) {
  if (formulas_.empty()) throw std::invalid_argument(role_ + ": no formula given");
  if (variables_.size() > kMaxVariables)
    throw std::invalid_argument(role_ + ": too many variables");
  // Each formula on its own first, so that an error points into what the user typed.
  for (const std::string& f : formulas_) {
    const std::string shown = quoted_line(f);
    if (f.find_first_not_of(" \t") == std::string::npos)
      throw std::invalid_argument(role_ + " is empty; type a formula in " + variable_list());
    Instance probe;
    define_names(probe.parser, variables_, probe.storage);
    try {
      probe.parser.SetExpr(f);
      probe.parser.Eval();  // muparser parses lazily, on the first evaluation
    } catch (const mu::Parser::exception_type& e) {
      if (e.GetCode() == mu::ecUNASSIGNABLE_TOKEN) {
        throw std::invalid_argument(role_ + " " + shown + ": unknown name '" + e.GetToken() +
                                    "' at position " + std::to_string(e.GetPos() + 1) +
                                    "; the variables are " + variable_list() +
                                    " and the constants pi, e");
      }
      throw std::invalid_argument(role_ + " " + shown + ": " + one_line(e.GetMsg()));
    }
    if (probe.parser.GetNumResults() != 1)
      throw std::invalid_argument(role_ + " " + shown +
                                  ": one formula expected, found a comma-separated list");
  }
  for (const std::string& f : formulas_) {
    if (!joined_.empty()) joined_.push_back(',');
    joined_.append(f);
  }
  // The tape is read off the bytecode of the joined formulas, with each variable's storage
  // telling the translator which input a variable token reads.
  Instance parsed;
  define_names(parsed.parser, variables_, parsed.storage);
  parsed.parser.SetExpr(joined_);
  parsed.parser.Eval();
  double* inputs[kMaxVariables];
  for (std::size_t i = 0; i < variables_.size(); ++i) inputs[i] = &parsed.storage[i];
  if (std::optional<FormulaTape> tape =
          FormulaTape::translate(parsed.parser, std::span(inputs, variables_.size())))
    tape_ = std::make_unique<const FormulaTape>(std::move(*tape));
}

std::optional<FormulaTape> Expression::tape_with(std::string_view variable, double value) const {
  if (!tape_) return std::nullopt;
  const auto it = std::find(variables_.begin(), variables_.end(), variable);
  if (it == variables_.end()) return *tape_;
  return tape_->bind(static_cast<int>(it - variables_.begin()), value);
}

Expression::~Expression() = default;

std::string Expression::variable_list() const {
  std::string list;
  for (const std::string& v : variables_) {
    if (!list.empty()) list.append(", ");
    list.append(v);
  }
  return list;
}

Expression::Instance& Expression::local_instance() const {
  struct Entry {
    std::uint64_t serial;
    std::unique_ptr<Instance> instance;
  };
  // Most recently used first; the front entry is the common hit.
  thread_local std::vector<Entry> cache;
  for (std::size_t i = 0; i < cache.size(); ++i) {
    if (cache[i].serial != serial_) continue;
    if (i > 0)
      std::rotate(cache.begin(), cache.begin() + static_cast<std::ptrdiff_t>(i),
                  cache.begin() + static_cast<std::ptrdiff_t>(i) + 1);
    return *cache.front().instance;
  }
  // First use in this thread: parse (allocates, once). The formulas were validated by the
  // constructor, so this cannot fail.
  auto instance = std::make_unique<Instance>();
  define_names(instance->parser, variables_, instance->storage);
  instance->parser.SetExpr(joined_);
  instance->parser.Eval();
  if (cache.size() >= kThreadCacheSize) cache.pop_back();
  cache.insert(cache.begin(), Entry{serial_, std::move(instance)});
  return *cache.front().instance;
}

void Expression::evaluate(std::span<const double> values, std::span<double> out) const {
  if (tape_ && tape_->outputs() <= FormulaTape::kLocalStack) {
    ForwardJet<0, 0> results[FormulaTape::kLocalStack];
    tape_->evaluate<0, 0>(values, results);
    const std::size_t n = std::min(out.size(), static_cast<std::size_t>(tape_->outputs()));
    for (std::size_t i = 0; i < n; ++i) out[i] = results[i].value;
    return;
  }
  Instance& in = local_instance();
  std::copy_n(values.begin(), std::min(values.size(), variables_.size()), in.storage);
  int n = 0;
  const double* results = in.parser.Eval(n);
  std::copy_n(results, std::min(out.size(), static_cast<std::size_t>(n)), out.begin());
}

double Expression::value(std::span<const double> values) const {
  if (tape_) {
    ForwardJet<0, 0> results[FormulaTape::kLocalStack];
    tape_->evaluate<0, 0>(values, results);
    return results[0].value;
  }
  Instance& in = local_instance();
  std::copy_n(values.begin(), std::min(values.size(), variables_.size()), in.storage);
  if (formulas_.size() == 1) return in.parser.Eval();
  int n = 0;
  return in.parser.Eval(n)[0];
}

}  // namespace dynamesh
