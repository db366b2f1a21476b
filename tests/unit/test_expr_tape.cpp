// Typed formulas' tapes (formula_tape.h): values against muparser's own evaluation for every
// operation muparser 2.3.3 knows, jet derivatives against high-order finite differences of
// values, the t-bound tape against the full one, evaluation from many threads at once, the
// choices at points where a derivative does not exist, and the fallback when the bytecode
// holds something the translator does not know.
#include <gtest/gtest.h>
#include <muParser.h>
#include <omp.h>

#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "core/surface/expression/expression.h"
#include "core/surface/expression/formula_tape.h"
#include "core/surface/expression/implicit_expression_surface.h"

namespace dynamesh {
namespace {

using Point = std::array<double, 4>;  // x, y, z, t

// Every operator, muparser rewrite (VARMUL, VARPOW, constant folding), branch kind and
// default function, with arguments mostly inside the functions' domains; the last group
// leaves them on purpose (NaN and infinity must agree too).
const std::vector<std::string> kFormulas = {
    // arithmetic, and the bytecode muparser's optimiser makes of it
    "x + y - z * t / 3",
    "2*x + 1",
    "x*3 - 2",
    "x + x",
    "3*(2*y+1)",
    "4*z/2",
    "x - 5",
    "-x",
    "-(x + y)",
    "+x",
    "+(x*y)",
    "-(-x)",
    "2 - -y",
    "x^2 + y^3 + z^4",
    "x*x",
    "(x+y)^2",
    "(x-y)^3",
    "(x*z)^4",
    "(x^2+1)^0.5",
    "x^0",
    "x^1",
    "(x^2+0.5)^-2",
    "(x*y+5)^-1.5",
    "(y+3)^x",
    "2^x",
    "abs(x)^y",
    "(x^2+0.1)^(y/2)",
    "t^2 * x^3",
    "x / (y^2 + 0.5)",
    "1 / (x^2 + y^2 + 0.01)",
    "x*y*z - x/(1+z^2)",
    // comparisons, logic and branches
    "x < y",
    "x <= y",
    "x > y",
    "x >= y",
    "x == y",
    "x != y",
    "x > 0 && y > 0",
    "x > 0 || y > 0",
    "x > 0 ? x^2 : -x^3",
    "x > y ? (z > 0 ? sin(z) : cos(z)) : x*y",
    "(x > 0 ? 1 : 2) + 3*y",
    "x < 0.5 ? (y < 0 ? x : y) : z*t",
    "(x > 0 && y < 1) ? exp(x) : (z < 0 || t > 0 ? z : 2*y)",
    "y + (x > 0 ? 2 : x)^2",
    // functions
    "sin(x)",
    "cos(x)",
    "tan(x/1.7)",
    "asin(x/2.5)",
    "acos(y/2.5)",
    "atan(x*y)",
    "atan2(y, x)",
    "sinh(x)",
    "cosh(y)",
    "tanh(x*z)",
    "asinh(3*x)",
    "acosh(x^2 + 1.5)",
    "atanh(y / 2.5)",
    "log2(x^2 + 0.3)",
    "log10(abs(y) + 0.1)",
    "log(x^2 + 0.5)",
    "ln(y^2+1)",
    "exp(-x^2)",
    "sqrt(x^2 + y^2 + z^2)",
    "sign(x) * y",
    "rint(3*x) + y",
    "abs(x - y)",
    "min(x, y)",
    "max(x, y, z)",
    "min(x, y, z, t)",
    "sum(x)",
    "sum(x, y, z)",
    "avg(x, y)",
    "avg(x, y, z, t)",
    "max(x^2, 0.5)",
    "min(sin(x), cos(y)) * max(z, -z)",
    // constants and time
    "pi * e * x",
    "sin(2*pi*t) * x",
    "0.6*(9/0.6)^t - y",
    // the examples (assets/examples) and the benchmarks
    "(x/(1+0.3*sin(2*pi*t)))^2 + (y/0.7)^2 + (z/(0.5-0.2*sin(2*pi*t)))^2 - 1",
    "sqrt((sqrt(x^2+y^2)-1)^2+z^2) - 0.4 - 0.1*sin(2*pi*t)",
    "sqrt(x^2+y^2+z^2) - 0.8*(1 + 0.3*sin(2*pi*t)*sin(4*x)*sin(4*y)*sin(4*z))",
    "0.12*sin(2*pi*(1.5*x + z - 2*t))*exp(-x^2)",
    "0.6*sin(2*pi*t)*(sqrt(x^2+z^2) < 1e-9 ? 1 : "
    "sin(4*pi*sqrt(x^2+z^2))/(4*pi*sqrt(x^2+z^2)))*exp(-0.5*sqrt(x^2+z^2))",
    // outside the domains
    "asin(x)",
    "acosh(y)",
    "sqrt(x)",
    "log(x)",
    "x / 0",
    "1/x",
    "x^0.5",
    "(x-y)^y",
    "x^y",
};

// A formula parsed by a muparser of its own (the reference) and translated.
struct Parsed {
  explicit Parsed(const std::string& formula) {
    parser.DefineConst("pi", std::numbers::pi);
    parser.DefineConst("e", std::numbers::e);
    const char* names[] = {"x", "y", "z", "t"};
    for (int i = 0; i < 4; ++i) parser.DefineVar(names[i], &storage[i]);
    parser.SetExpr(formula);
    parser.Eval();
    double* inputs[4] = {&storage[0], &storage[1], &storage[2], &storage[3]};
    tape = FormulaTape::translate(parser, inputs);
  }
  double reference(const Point& p) {
    for (int i = 0; i < 4; ++i) storage[i] = p[static_cast<std::size_t>(i)];
    return parser.Eval();
  }
  mu::Parser parser;
  double storage[4] = {};
  std::optional<FormulaTape> tape;
};

// Through both of evaluate()'s paths: its own stack and a copy, or the caller's stack; they
// must agree exactly.
template <int N, int Order>
ForwardJet<N, Order> jet_at(const FormulaTape& tape, const Point& p) {
  ForwardJet<N, Order> copied, stack[FormulaTape::kLocalStack + 16];
  tape.evaluate<N, Order>(p, std::span(&copied, 1));
  tape.evaluate<N, Order>(p, stack);
  EXPECT_EQ(std::memcmp(&copied, &stack[0], sizeof copied), 0);
  return copied;
}

double value_at(const FormulaTape& tape, const Point& p) {
  return jet_at<0, 0>(tape, p).value;
}

bool same_value(double a, double b) {
  if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b);
  return a == b || std::abs(a - b) <= 1e-14 * std::abs(b);
}

// Random points in [-2, 2]^4, and points on the edges of functions (zeros, ties, integers).
std::vector<Point> test_points(int count, unsigned seed) {
  std::vector<Point> points = {{0, 0, 0, 0},           {1, 1, 1, 1},     {-1, -1, 0.5, 0},
                               {0.5, 0.5, -0.5, 0.25}, {2, -2, 0, 1},    {-0.5, 0, 0, -1},
                               {0, 1.5, -1.5, 0.5},    {-2, 3, 1e-3, 0}, {1e-12, -1e-12, 0, 0.3}};
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  while (static_cast<int>(points.size()) < count)
    points.push_back({u(rng), u(rng), u(rng), u(rng)});
  return points;
}

TEST(ExprTape, TranslatesEveryDefaultOperation) {
  for (const std::string& f : kFormulas) EXPECT_TRUE(Parsed(f).tape.has_value()) << f;
}

TEST(ExprTape, ValuesEqualMuparsersAtManyPoints) {
  const std::vector<Point> points = test_points(400, 1);
  for (const std::string& f : kFormulas) {
    Parsed parsed(f);
    ASSERT_TRUE(parsed.tape) << f;
    for (const Point& p : points) {
      const double expected = parsed.reference(p);
      const double got = value_at(*parsed.tape, p);
      ASSERT_TRUE(same_value(got, expected))
          << f << " at " << p[0] << ", " << p[1] << ", " << p[2] << ", " << p[3] << ": tape " << got
          << ", muparser " << expected;
      // Jets carry the same value.
      ASSERT_TRUE(same_value(jet_at<3, 1>(*parsed.tape, p).value, got)) << f;
      ASSERT_TRUE(same_value(jet_at<2, 2>(*parsed.tape, p).value, got)) << f;
      ASSERT_TRUE(same_value(jet_at<3, 2>(*parsed.tape, p).value, got)) << f;
    }
  }
}

TEST(ExprTape, SeveralFormulasGiveOneResultEach) {
  const Expression e({"x + y", "x > 0 ? x*y : sin(y)", "max(x, y, 1)"}, {"x", "y"}, "test formula");
  ASSERT_TRUE(e.differentiable());
  ASSERT_EQ(e.tape()->outputs(), 3);
  for (const Point& p : test_points(100, 2)) {
    const double in[2] = {p[0], p[1]};
    double expected[3];
    e.evaluate(in, expected);
    ForwardJet<2, 2> got[3];
    e.tape()->evaluate<2, 2>(in, got);  // a stack too small: copied from its own
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(same_value(got[k].value, expected[k])) << k;
  }
}

TEST(ExprTape, BoundTimeGivesTheFullTapesResults) {
  const std::vector<Point> points = test_points(100, 3);
  for (const std::string& f : kFormulas) {
    Parsed parsed(f);
    ASSERT_TRUE(parsed.tape) << f;
    for (const Point& p : points) {
      const FormulaTape bound = parsed.tape->bind(3, p[3]);
      EXPECT_LE(bound.ops().size(), parsed.tape->ops().size());
      const Point other_time = {p[0], p[1], p[2], p[3] + 0.37};  // the bound tape ignores t
      const auto a = jet_at<3, 2>(bound, other_time), b = jet_at<3, 2>(*parsed.tape, p);
      // The same operations in the same order: equal, except that a folded 0 derivative may
      // have lost its sign.
      ASSERT_TRUE(same_value(a.value, b.value)) << f;
      for (int i = 0; i < 3; ++i) ASSERT_TRUE(same_value(a.grad[i], b.grad[i])) << f;
      for (int k = 0; k < 6; ++k) ASSERT_TRUE(same_value(a.hess[k], b.hess[k])) << f;
    }
  }
  // Terms in t alone become one constant: the sphere of the benchmark is x^2, + y^2, + z^2,
  // a root, - a constant, the end.
  Parsed sphere("sqrt(x^2+y^2+z^2) - 0.6*(9/0.6)^t");
  EXPECT_EQ(sphere.tape->ops().size(), 11u);  // ... 0.6, 15, t, ^, *, -, the end
  EXPECT_EQ(sphere.tape->bind(3, 0.3).ops().size(), 6u);
}

// Five-point central differences of the tape's values (muparser's, by the test above):
// gradient and Hessian with respect to x, y, z.
struct Differences {
  std::array<double, 3> grad;
  std::array<std::array<double, 3>, 3> hess;
};

Differences differences(const FormulaTape& tape, const Point& p, double h) {
  auto f = [&](int i, double di, int j, double dj) {
    Point q = p;
    q[static_cast<std::size_t>(i)] += di;
    q[static_cast<std::size_t>(j)] += dj;
    return value_at(tape, q);
  };
  auto d1 = [&](int i, int j, double dj) {
    return (-f(i, 2 * h, j, dj) + 8 * f(i, h, j, dj) - 8 * f(i, -h, j, dj) + f(i, -2 * h, j, dj)) /
           (12 * h);
  };
  Differences d;
  for (int i = 0; i < 3; ++i) {
    d.grad[static_cast<std::size_t>(i)] = d1(i, i, 0.0);
    d.hess[static_cast<std::size_t>(i)][static_cast<std::size_t>(i)] =
        (-f(i, 2 * h, i, 0) + 16 * f(i, h, i, 0) - 30 * f(i, 0, i, 0) + 16 * f(i, -h, i, 0) -
         f(i, -2 * h, i, 0)) /
        (12 * h * h);
    for (int j = 0; j < i; ++j) {
      const double dij =
          (-d1(i, j, 2 * h) + 8 * d1(i, j, h) - 8 * d1(i, j, -h) + d1(i, j, -2 * h)) / (12 * h);
      d.hess[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] = dij;
      d.hess[static_cast<std::size_t>(j)][static_cast<std::size_t>(i)] = dij;
    }
  }
  return d;
}

TEST(ExprTape, JetsAgreeWithFiniteDifferences) {
  // Where the formula is smooth at the stencil's scale (the differences with steps h and 2h
  // agree), the jet's derivatives must match them; near a kink, a jump or a pole they are
  // skipped, so the count of points checked is asserted too.
  constexpr double h = 2e-3;
  const std::vector<Point> points = test_points(120, 4);
  int checked = 0, total = 0;
  for (const std::string& f : kFormulas) {
    Parsed parsed(f);
    ASSERT_TRUE(parsed.tape) << f;
    int checked_here = 0;
    for (const Point& p : points) {
      ++total;
      const auto jet = jet_at<3, 2>(*parsed.tape, p);
      const auto first = jet_at<3, 1>(*parsed.tape, p);
      const Differences fine = differences(*parsed.tape, p, h);
      const Differences coarse = differences(*parsed.tape, p, 2 * h);
      bool smooth = std::isfinite(jet.value);
      for (int i = 0; i < 3; ++i) {
        const std::size_t a = static_cast<std::size_t>(i);
        smooth = smooth && std::isfinite(fine.grad[a]) &&
                 std::abs(fine.grad[a] - coarse.grad[a]) <= 1e-8 * (1 + std::abs(fine.grad[a]));
        for (std::size_t b = 0; b < 3; ++b)
          smooth = smooth && std::isfinite(fine.hess[a][b]) &&
                   std::abs(fine.hess[a][b] - coarse.hess[a][b]) <=
                       1e-5 * (1 + std::abs(fine.hess[a][b]));
      }
      if (!smooth) continue;
      ++checked;
      ++checked_here;
      for (int i = 0; i < 3; ++i) {
        const std::size_t a = static_cast<std::size_t>(i);
        EXPECT_NEAR(jet.grad[a], fine.grad[a], 1e-7 * (1 + std::abs(fine.grad[a])))
            << f << " d/d"
            << "xyz"[i] << " at " << p[0] << ", " << p[1] << ", " << p[2] << ", " << p[3];
        EXPECT_EQ(first.grad[a], jet.grad[a]) << f;  // the orders agree exactly
        for (int j = 0; j < 3; ++j)
          EXPECT_NEAR(jet.hessian(i, j), fine.hess[a][static_cast<std::size_t>(j)],
                      1e-4 * (1 + std::abs(fine.hess[a][static_cast<std::size_t>(j)])))
              << f << " d2/d"
              << "xyz"[i] << "d"
              << "xyz"[j] << " at " << p[0] << ", " << p[1] << ", " << p[2] << ", " << p[3];
      }
      // Two inputs: the same numbers for x and y.
      const auto two = jet_at<2, 2>(*parsed.tape, p);
      EXPECT_EQ(two.grad[1], jet.grad[1]) << f;
      EXPECT_EQ(two.hessian(0, 1), jet.hessian(0, 1)) << f;
    }
    const bool nowhere_finite = f == "x / 0";
    if (!nowhere_finite) {
      EXPECT_GT(checked_here, 0) << f;
    }
  }
  EXPECT_GT(checked, total * 7 / 10);
}

TEST(ExprTape, ChoicesWhereDerivativesDoNotExist) {
  auto jet = [](const std::string& f, const Point& p) {
    Parsed parsed(f);
    EXPECT_TRUE(parsed.tape) << f;
    return jet_at<3, 2>(*parsed.tape, p);
  };
  auto all_zero = [](const ForwardJet<3, 2>& j) {
    for (double g : j.grad)
      if (g != 0.0) return false;
    for (double h : j.hess)
      if (h != 0.0) return false;
    return true;
  };
  // The tip of a cone: value 0, derivatives 0 (central differences give a zero gradient
  // there too), never NaN.
  const ForwardJet<3, 2> cone = jet("sqrt(x^2+y^2+z^2) - 1", {0, 0, 0, 0});
  EXPECT_EQ(cone.value, -1.0);
  EXPECT_TRUE(all_zero(cone));
  EXPECT_TRUE(all_zero(jet("(x^2+y^2)^0.5", {0, 0, 0.3, 0})));
  // A crease: |x| at 0 has the central difference 0.
  EXPECT_EQ(jet("abs(x) + y", {0, 0.5, 0, 0}).grad[0], 0.0);
  // Ties of min and max: the average of the tied arguments' derivatives.
  const ForwardJet<3, 2> tie = jet("min(x, y, 2*z)", {0.5, 0.5, 0.25, 0});
  EXPECT_EQ(tie.grad[0], 1.0 / 3.0);
  EXPECT_EQ(tie.grad[1], 1.0 / 3.0);
  EXPECT_EQ(tie.grad[2], 2.0 / 3.0);
  // Squares and cubes of negative numbers: the product rule, not exp(p log x).
  for (const char* f : {"(x+y)^2", "(x+y)^3", "x^2", "x^y"}) {
    const ForwardJet<3, 2> j = jet(f, {-1.5, f[1] == '+' ? -0.5 : 2.0, 0, 0});
    for (double g : j.grad) EXPECT_TRUE(std::isfinite(g)) << f;
    for (double h : j.hess) EXPECT_TRUE(std::isfinite(h)) << f;
  }
  EXPECT_EQ(jet("(x+y)^2", {-1.5, -0.5, 0, 0}).grad[0], -4.0);
  EXPECT_EQ(jet("(x+y)^3", {-1.5, -0.5, 0, 0}).hessian(0, 1), -12.0);
  // 0^p: for p > 1 the derivative exists and is 0.
  const ForwardJet<3, 2> zero_power = jet("x^y", {0, 2, 0, 0});
  EXPECT_EQ(zero_power.value, 0.0);
  EXPECT_EQ(zero_power.grad[0], 0.0);
  EXPECT_EQ(zero_power.grad[1], 0.0);
  // The edge of a domain: the one-sided derivative, infinite, and 0 where the argument does
  // not depend on the input.
  const ForwardJet<3, 2> edge = jet("sqrt(x) + y", {0, 1, 0, 0});
  EXPECT_EQ(edge.grad[0], std::numeric_limits<double>::infinity());
  EXPECT_EQ(edge.grad[1], 1.0);
  EXPECT_EQ(edge.grad[2], 0.0);
  // t is not differentiated; a branch on it is a constant choice.
  const ForwardJet<3, 2> timed = jet("t > 0 ? x*t : y", {2, 3, 4, 0.5});
  EXPECT_EQ(timed.grad[0], 0.5);
  EXPECT_EQ(timed.grad[1], 0.0);
}

TEST(ExprTape, ThreadsGetIdenticalResults) {
  // A formula deeper than the tape's local stack too, so that the per-thread scratch stack is
  // used as well.
  std::string deep = "x";
  for (int i = 0; i < FormulaTape::kLocalStack + 8; ++i)
    deep = "sin(y*" + std::to_string(i + 1) + ")+(" + deep + ")*z";
  for (const std::string& f :
       {std::string("sqrt((sqrt(x^2+y^2)-1)^2+z^2) - 0.4 - 0.1*sin(2*pi*t)"), deep}) {
    Parsed parsed(f);
    ASSERT_TRUE(parsed.tape) << f;
    if (f == deep) {
      EXPECT_GT(parsed.tape->max_depth(), FormulaTape::kLocalStack);
    }
    const std::vector<Point> points = test_points(4000, 5);
    const int n = static_cast<int>(points.size());
    std::vector<ForwardJet<3, 2>> serial(points.size()), parallel(points.size());
    for (int i = 0; i < n; ++i)
      serial[static_cast<std::size_t>(i)] =
          jet_at<3, 2>(*parsed.tape, points[static_cast<std::size_t>(i)]);
#pragma omp parallel for num_threads(4) schedule(dynamic, 16)
    for (int i = 0; i < n; ++i)
      parallel[static_cast<std::size_t>(i)] =
          jet_at<3, 2>(*parsed.tape, points[static_cast<std::size_t>(i)]);
    for (int i = 0; i < n; ++i) {
      const auto& a = serial[static_cast<std::size_t>(i)];
      const auto& b = parallel[static_cast<std::size_t>(i)];
      ASSERT_TRUE(same_value(a.value, b.value)) << i;
      ASSERT_TRUE(a.value == b.value || std::isnan(a.value)) << i;
      for (int k = 0; k < 3; ++k) ASSERT_TRUE(a.grad[k] == b.grad[k] || std::isnan(a.grad[k]));
      for (int k = 0; k < 6; ++k) ASSERT_TRUE(a.hess[k] == b.hess[k] || std::isnan(a.hess[k]));
      ASSERT_TRUE(same_value(a.value, parsed.reference(points[static_cast<std::size_t>(i)])));
    }
  }
}

double twice(double v) {
  return 2 * v;
}
double my_sin(double v) {
  return std::sin(v) + 1.0;
}

TEST(ExprTape, UnknownBytecodeFallsBack) {
  double x = 0.3;
  {
    // A function of the parser's user: no tape where it is used, a tape where it is not.
    mu::Parser parser;
    parser.DefineVar("x", &x);
    parser.DefineFun("twice", twice);
    double* inputs[1] = {&x};
    parser.SetExpr("twice(x) + 1");
    parser.Eval();
    EXPECT_FALSE(FormulaTape::translate(parser, inputs));
    parser.SetExpr("sin(x) + 1");
    parser.Eval();
    EXPECT_TRUE(FormulaTape::translate(parser, inputs));
  }
  {
    // "sin" redefined: recognised by its address, not its name, so not taken for the sine.
    mu::Parser parser;
    parser.DefineVar("x", &x);
    parser.DefineFun("sin", my_sin);
    double* inputs[1] = {&x};
    parser.SetExpr("sin(x)");
    parser.Eval();
    EXPECT_FALSE(FormulaTape::translate(parser, inputs));
  }
  {
    // A variable the caller did not list as an input.
    mu::Parser parser;
    double y = 2.0;
    parser.DefineVar("x", &x);
    parser.DefineVar("y", &y);
    double* inputs[1] = {&x};
    parser.SetExpr("x + y");
    parser.Eval();
    EXPECT_FALSE(FormulaTape::translate(parser, inputs));
  }
  // What a user can type and the translator does not know: muparser's assignment. The
  // Expression then has no tape, and its surface falls back to muparser and differences.
  const std::string ellipsoid = "(x = 2*x)^2 + y^2 + z^2 - 1";  // 4x^2 + y^2 + z^2 = 1
  const Expression e({ellipsoid}, {"x", "y", "z", "t"}, "implicit formula");
  EXPECT_FALSE(e.differentiable());
  EXPECT_EQ(e.tape(), nullptr);
  EXPECT_FALSE(e.tape_with("t", 0.5));
  EXPECT_TRUE(Expression({"x^2 + y^2 + z^2 - 1"}, {"x", "y", "z", "t"}, "f").differentiable());
  const ImplicitExpressionSurface s(ellipsoid, Box3{Vec3::Constant(-2), Vec3::Constant(2)});
  for (const Vec3& p : {Vec3(0.2, 0.3, -0.4), Vec3(-0.4, 0.5, 0.6)}) {
    Vec3 g;
    EXPECT_DOUBLE_EQ(s.value_gradient(p, g), 4 * p.x() * p.x() + p.y() * p.y() + p.z() * p.z() - 1);
    // Central differences with h = 1e-5 * diagonal: exact for a quadratic up to rounding.
    EXPECT_NEAR((g - Vec3(8 * p.x(), 2 * p.y(), 2 * p.z())).norm(), 0.0, 1e-8);
    const Mat3 H = s.hessian(p);
    EXPECT_NEAR((H - Vec3(8, 2, 2).asDiagonal().toDenseMatrix()).norm(), 0.0, 1e-5);
  }
}

}  // namespace
}  // namespace dynamesh
