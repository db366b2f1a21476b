#include "bench/comparison_measure.h"

#include <omp.h>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <random>
#include <sstream>
#include <stdexcept>
#include <unordered_set>

#include "core/io/number_text.h"
#include "tests/unit/dense_error.h"

namespace dynamesh::compare {

TriangleSoup soup_of(const Mesh48& mesh) {
  TriangleSoup soup;
  std::vector<std::uint32_t> index(mesh.vertex_capacity(), 0);
  for (Vertex v : mesh.live_vertices()) {
    index[v.idx] = static_cast<std::uint32_t>(soup.points.size());
    soup.points.push_back(mesh.position(v));
  }
  for (Face f : mesh.live_faces()) {
    const auto v = mesh.vertices(f);
    soup.triangles.push_back({index[v[0].idx], index[v[1].idx], index[v[2].idx]});
  }
  return soup;
}

double dense_error(const ImplicitSurface& surface, const TriangleSoup& soup, int points_per_face,
                   std::uint64_t seed) {
  const auto n = static_cast<std::int64_t>(soup.triangles.size());
  const Vec2 uv[3] = {Vec2::Zero(), Vec2::Zero(), Vec2::Zero()};  // implicit: unused
  double worst = 0.0;
#pragma omp parallel for schedule(dynamic, 256) reduction(max      \
                                                          : worst) \
    num_threads(omp_get_num_procs())
  for (std::int64_t i = 0; i < n; ++i) {
    const auto& t = soup.triangles[static_cast<std::size_t>(i)];
    const Vec3 p[3] = {soup.points[t[0]], soup.points[t[1]], soup.points[t[2]]};
    std::mt19937_64 rng(seed * 1000003u + static_cast<std::uint64_t>(i));
    worst = std::max(worst, test::dense_triangle_error(surface, p, uv, points_per_face, rng));
  }
  return worst;
}

namespace {
struct PositionHash {
  std::size_t operator()(const std::array<std::uint64_t, 3>& k) const {
    return (k[0] * 0x9E3779B97F4A7C15ull) ^ (k[1] * 0xC2B2AE3D27D4EB4Full) ^
           (k[2] * 0x165667B19E3779F9ull);
  }
};
std::array<std::uint64_t, 3> bits_of(const Vec3& p) {
  std::array<std::uint64_t, 3> k;
  for (int i = 0; i < 3; ++i) std::memcpy(&k[static_cast<std::size_t>(i)], &p[i], 8);
  return k;
}
}  // namespace

double position_survival(const std::vector<Vec3>& before, const std::vector<Vec3>& after) {
  if (before.empty()) return 1.0;
  std::unordered_set<std::array<std::uint64_t, 3>, PositionHash> present;
  present.reserve(after.size());
  for (const Vec3& p : after) present.insert(bits_of(p));
  std::size_t kept = 0;
  for (const Vec3& p : before) kept += present.count(bits_of(p));
  return static_cast<double>(kept) / static_cast<double>(before.size());
}

namespace {
constexpr const char* kHeader =
    "method,scene,parameter,frames,threads,triangles_mean,triangles_max,dense_error_max,"
    "cpu_seconds_median,fill_cpu_seconds_median,wall_seconds_median,survival_mean";
}

void write_csv_header(std::ostream& out) {
  out << kHeader << '\n';
}

void write_csv_row(std::ostream& out, const ComparisonRow& r) {
  std::ostringstream line;
  line.precision(9);
  line << r.method << ',' << r.scene << ',' << r.parameter << ',' << r.frames << ',' << r.threads
       << ',' << r.triangles_mean << ',' << r.triangles_max << ',' << r.dense_error_max << ','
       << r.cpu_seconds_median << ',' << r.fill_cpu_seconds_median << ',' << r.wall_seconds_median
       << ',' << r.survival_mean << '\n';
  out << line.str();
}

ComparisonRow parse_csv_row(const std::string& line) {
  std::vector<std::string> field;
  std::stringstream in(line);
  for (std::string f; std::getline(in, f, ',');) field.push_back(f);
  if (field.size() != 12) throw std::invalid_argument("comparison CSV: expected 12 fields");
  const auto number = [&](std::size_t i) {
    const std::optional<double> x = parse_finite_number(field[i]);
    if (!x) throw std::invalid_argument("comparison CSV: bad number '" + field[i] + "'");
    return *x;
  };
  ComparisonRow r;
  r.method = field[0];
  r.scene = field[1];
  r.parameter = number(2);
  r.frames = static_cast<int>(number(3));
  r.threads = static_cast<int>(number(4));
  r.triangles_mean = number(5);
  r.triangles_max = number(6);
  r.dense_error_max = number(7);
  r.cpu_seconds_median = number(8);
  r.fill_cpu_seconds_median = number(9);
  r.wall_seconds_median = number(10);
  r.survival_mean = number(11);
  return r;
}

double interpolate_log_log(const std::vector<std::array<double, 2>>& curve, double error) {
  std::vector<std::array<double, 2>> c = curve;
  std::sort(c.begin(), c.end());
  for (std::size_t i = 1; i < c.size(); ++i) {
    if (error < c[i - 1][0] || error > c[i][0]) continue;
    const double s = c[i][0] == c[i - 1][0]
                         ? 0.0
                         : std::log(error / c[i - 1][0]) / std::log(c[i][0] / c[i - 1][0]);
    return std::exp(std::log(c[i - 1][1]) + s * std::log(c[i][1] / c[i - 1][1]));
  }
  return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace dynamesh::compare
