#include "core/surface/expression/formula_checks.h"

#include <cmath>
#include <functional>
#include <sstream>
#include <stdexcept>

namespace dynamesh {

namespace {

std::string time_text(double t) {
  std::ostringstream s;
  s << "t = " << t;
  return s.str();
}

}  // namespace

ImplicitScan scan_implicit(const Expression& f, const std::string& formula_text, const Box3& box,
                           double t, int n, const Vec3* extra_point) {
  const std::string what = "implicit formula '" + formula_text + "'";
  ImplicitScan scan;
  scan.min_value = HUGE_VAL;
  Vec3 negative_sum = Vec3::Zero();
  long negative_count = 0;
  // Non-finite values are reported before a surface leaving the box: they are the worse
  // mistake and the likelier cause.
  std::string escape;
  auto visit = [&](const Vec3& p, bool on_side) {
    const double x[4] = {p.x(), p.y(), p.z(), t};
    const double value = f.value(x);
    if (!std::isfinite(value))
      throw std::invalid_argument(what + " is " + (std::isnan(value) ? "NaN" : "infinite") +
                                  " at " + format_point(p) + ", " + time_text(t) +
                                  "; it must be finite everywhere inside --bounds");
    if (on_side && value < 0 && escape.empty())
      escape = what + " is negative at " + format_point(p) + " on the side of --bounds, " +
               time_text(t) +
               ": the surface must lie inside the bounds with F > 0 outside (enlarge --bounds, "
               "or negate F if it is positive inside)";
    if (value < scan.min_value) scan.min_value = value, scan.interior = p;
    if (value < 0) negative_sum += p, ++negative_count;
  };
  const Vec3 size = box.size();
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const Vec3 s(static_cast<double>(i) / (n - 1), static_cast<double>(j) / (n - 1),
                     static_cast<double>(k) / (n - 1));
        const bool on_side = i == 0 || j == 0 || k == 0 || i == n - 1 || j == n - 1 || k == n - 1;
        visit(box.min + s.cwiseProduct(size), on_side);
      }
  if (extra_point) visit(*extra_point, false);
  if (!escape.empty()) throw std::invalid_argument(escape);
  if (!(scan.min_value < 0))
    throw std::invalid_argument(
        what + " has no zero crossing inside --bounds at " + time_text(t) +
        ": it is positive everywhere (smallest value " + std::to_string(scan.min_value) + " at " +
        format_point(scan.interior) + "); the surface is F = 0 with F < 0 inside");
  // The centroid of the inside is a better centre for a star-shaped surface than its deepest
  // point (which can sit near one end of an elongated shape).
  const Vec3 centroid = negative_sum / static_cast<double>(std::max(1L, negative_count));
  const double x[4] = {centroid.x(), centroid.y(), centroid.z(), t};
  if (f.value(x) < 0) scan.interior = centroid;
  return scan;
}

Box3 scan_parametric(const std::function<Vec3(const Vec2&)>& position,
                     const std::string& role_and_formula, const ParameterDomain& domain, double t,
                     int n) {
  Box3 box;
  const Vec2 size = domain.max - domain.min;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Vec2 uv =
          domain.min + Vec2(static_cast<double>(i) / (n - 1), static_cast<double>(j) / (n - 1))
                           .cwiseProduct(size);
      const Vec3 p = position(uv);
      if (!p.allFinite())
        throw std::invalid_argument(role_and_formula + " is not finite at " + format_point(uv) +
                                    ", " + time_text(t) +
                                    "; it must be finite everywhere on the domain");
      box.extend(p);
    }
  // A periodic direction must close up: S at the domain's two ends must be the same point,
  // within rounding relative to the surface's size.
  const double tolerance = 1e-7 * std::max(box.diagonal(), 1e-300);
  for (int axis = 0; axis < 2; ++axis) {
    if (!(axis == 0 ? domain.periodic_u : domain.periodic_v)) continue;
    const char name = "uv"[axis];
    for (int k = 0; k < n; ++k) {
      Vec2 a = domain.min, b = domain.max;
      const int other = 1 - axis;
      a[other] = b[other] = domain.min[other] + size[other] * k / (n - 1);
      b[axis] = domain.max[axis];
      a[axis] = domain.min[axis];
      const Vec3 pa = position(a), pb = position(b);
      if ((pa - pb).norm() > tolerance)
        throw std::invalid_argument(role_and_formula + " is not periodic in " + name + " at " +
                                    time_text(t) + ": S" + format_point(a) + " = " +
                                    format_point(pa) + " but S" + format_point(b) + " = " +
                                    format_point(pb) + "; make the " + name +
                                    " range exactly one period (e.g. --domain 0,2*pi,...) or "
                                    "drop --periodic " +
                                    name);
    }
  }
  return box;
}

}  // namespace dynamesh
