// The published comparison of issue 17: dynamesh's adapted mesh against re-meshing every frame
// with OpenVDB (a narrow-band grid of the surface's first-order distance F / |grad F| at the
// voxel corners, meshed by tools::volumeToMesh with adaptivity 0), on the analytic scenes
// sphere, capsule-bend and twist, over the same animation. For every threshold T and voxel
// size h it records the triangles, the dense L-infinity error (comparison_measure.h: the same
// measurement for both meshes), the time per frame and the vertices kept from one frame to the
// next, and writes one CSV row per configuration; bench/plot_comparison.gp draws the plots of
// the README. Run by scripts/compare-openvdb.sh. Bad options: one line on stderr, exit 2.
#include <omp.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/SignedFloodFill.h>
#include <openvdb/tools/VolumeToMesh.h>
#include <tbb/global_control.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/comparison_measure.h"
#include "core/adapt/adapter.h"
#include "core/io/number_text.h"
#include "core/surface/scene_registry.h"
#include "tests/support/error_only_adapter.h"

namespace dynamesh::compare {
namespace {

struct Config {
  std::vector<std::string> scenes{"sphere", "capsule-bend", "twist"};
  std::vector<double> thresholds{4e-3, 2e-3, 1e-3, 5e-4};
  // Voxel sizes per scene, spanning the errors of the thresholds above (a factor sqrt 2
  // apart): the sphere's OpenVDB error at a given h is far below the twisted bar's, whose
  // Lp cross-section has tightly curved corners.
  std::map<std::string, std::vector<double>> voxels{
      {"sphere", {0.16, 0.113, 0.08, 0.056, 0.04, 0.028}},
      {"capsule-bend", {0.08, 0.056, 0.04, 0.028, 0.02, 0.014}},
      {"twist", {0.04, 0.028, 0.02, 0.014, 0.01, 0.007}}};
  int frames = 100;        // steps over t in [0, 1]
  int measure_every = 10;  // dense measurement at frames 0, K, 2K, ..., frames
  int points_per_face = 10;
  bool cull = true;  // skip grid leaves whose centre is far from the surface
  // Threads of both methods (OpenMP for dynamesh and the grid fill, TBB for volumeToMesh).
  int threads = 1;
  std::string out = "comparison.csv";
};

// Wall-clock and process CPU time together.
struct Stopwatch {
  std::chrono::steady_clock::time_point wall = std::chrono::steady_clock::now();
  double cpu = cpu_now();
  static double cpu_now() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
  }
  double cpu_seconds() const { return cpu_now() - cpu; }
  double wall_seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall).count();
  }
};

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

// The scene at t = 0. The sphere grows from R = 1 to 1.5 over the run (its default, 0.6 to
// 9, spans a factor 225 in area: the comparison would be about the largest frames only).
std::unique_ptr<ImplicitSurface> scene_at_start(const std::string& name) {
  std::unique_ptr<Surface> s = make_scene(name);
  if (name == "sphere") {
    s->set_parameter("R0", 1.0);
    s->set_parameter("R1", 1.5);
  }
  s->set_time(0.0);
  auto* implicit = dynamic_cast<ImplicitSurface*>(s.get());
  if (!implicit) throw std::invalid_argument("scene '" + name + "' is not implicit");
  s.release();
  return std::unique_ptr<ImplicitSurface>(implicit);
}

bool measured_frame(const Config& c, int k) {
  return k % c.measure_every == 0 || k == c.frames;
}

// dynamesh at threshold T (eps = T / 4, the geometric error everywhere, as in the accuracy
// tests; the sphere's multi-criteria default would leave half of it unbounded).
ComparisonRow run_dynamesh(const Config& c, const std::string& scene, double threshold) {
  auto surface = scene_at_start(scene);
  AdaptOptions o;
  o.threshold = threshold;
  o.epsilon = threshold / 4;
  const std::unique_ptr<Adapter> owned = test::error_only_adapter(*surface, o);
  Adapter& adapter = *owned;
  ComparisonRow row{"dynamesh", scene, threshold, c.frames, c.threads};
  std::vector<double> cpu, wall, survival, triangles;
  row.dense_error_max = dense_error(*surface, soup_of(adapter.mesh()), c.points_per_face, 1);
  for (int k = 1; k <= c.frames; ++k) {
    const Stopwatch watch;
    const StepStats& stats = adapter.step(static_cast<double>(k) / c.frames);
    cpu.push_back(watch.cpu_seconds());
    wall.push_back(watch.wall_seconds());
    survival.push_back(stats.kept_fraction);
    triangles.push_back(static_cast<double>(stats.triangles));
    if (measured_frame(c, k))
      row.dense_error_max =
          std::max(row.dense_error_max,
                   dense_error(*surface, soup_of(adapter.mesh()), c.points_per_face, 1 + k));
  }
  row.triangles_mean = mean(triangles);
  row.triangles_max = *std::max_element(triangles.begin(), triangles.end());
  row.cpu_seconds_median = median(cpu);
  row.wall_seconds_median = median(wall);
  row.survival_mean = mean(survival);
  return row;
}

// The narrow-band grid of F / |grad F| at voxel size h (index (i, j, k) at world h (i, j, k)),
// built leaf by leaf (8^3 voxels) in parallel. A leaf is skipped when its centre's distance
// estimate exceeds twice the leaf's half-diagonal plus the band: the estimate is exact on the
// sphere and within a few percent on the bent capsule and the twisted bar near their
// surfaces, so the factor 2 keeps every leaf the surface crosses (checked with --no-cull:
// the same triangle counts). Inside tiles get the negative background by a signed flood fill.
openvdb::FloatGrid::Ptr distance_grid(const ImplicitSurface& surface, double h, bool cull) {
  using Leaf = openvdb::FloatTree::LeafNodeType;
  const float band = static_cast<float>(3.0 * h);
  auto grid = openvdb::FloatGrid::create(band);
  grid->setTransform(openvdb::math::Transform::createLinearTransform(h));
  grid->setGridClass(openvdb::GRID_LEVEL_SET);
  const Box3 box = surface.bounds();
  const auto leaf_floor = [&](double x) { return static_cast<int>(std::floor(x / h / 8.0)) * 8; };
  std::vector<openvdb::Coord> origins;
  for (int i = leaf_floor(box.min.x() - 2 * h); i <= leaf_floor(box.max.x() + 2 * h); i += 8)
    for (int j = leaf_floor(box.min.y() - 2 * h); j <= leaf_floor(box.max.y() + 2 * h); j += 8)
      for (int k = leaf_floor(box.min.z() - 2 * h); k <= leaf_floor(box.max.z() + 2 * h); k += 8)
        origins.emplace_back(i, j, k);
  const auto distance = [&](const Vec3& p) {
    Vec3 g;
    const double f = surface.value_gradient(p, g);
    const double n = g.norm();
    return n > 1e-12 ? f / n : (f < 0 ? -1e300 : 1e300);
  };
  const double skip_beyond = 2.0 * std::sqrt(3.0) * 4.0 * h + 3.0 * h;
  std::vector<Leaf*> leaves(origins.size(), nullptr);
  const auto n = static_cast<std::int64_t>(origins.size());
#pragma omp parallel for schedule(dynamic, 16)
  for (std::int64_t l = 0; l < n; ++l) {
    const openvdb::Coord o = origins[static_cast<std::size_t>(l)];
    const Vec3 centre = h * Vec3(o.x() + 3.5, o.y() + 3.5, o.z() + 3.5);
    if (cull && std::abs(distance(centre)) > skip_beyond) continue;
    auto* leaf = new Leaf(o, band);
    for (openvdb::Index v = 0; v < Leaf::SIZE; ++v) {
      const openvdb::Coord xyz = leaf->offsetToGlobalCoord(v);
      const double d = distance(h * Vec3(xyz.x(), xyz.y(), xyz.z()));
      leaf->setValueOn(v, static_cast<float>(std::clamp(d, -3.0 * h, 3.0 * h)));
    }
    leaves[static_cast<std::size_t>(l)] = leaf;
  }
  for (Leaf* leaf : leaves)
    if (leaf) grid->tree().addLeaf(leaf);
  openvdb::tools::signedFloodFill(grid->tree());
  return grid;
}

TriangleSoup mesh_of(const openvdb::FloatGrid& grid) {
  std::vector<openvdb::Vec3s> points;
  std::vector<openvdb::Vec3I> triangles;
  std::vector<openvdb::Vec4I> quads;
  openvdb::tools::volumeToMesh(grid, points, triangles, quads, 0.0, 0.0);
  TriangleSoup soup;
  soup.points.reserve(points.size());
  for (const openvdb::Vec3s& p : points) soup.points.emplace_back(p.x(), p.y(), p.z());
  for (const openvdb::Vec3I& t : triangles) soup.triangles.push_back({t[0], t[1], t[2]});
  for (const openvdb::Vec4I& q : quads) {
    soup.triangles.push_back({q[0], q[1], q[2]});
    soup.triangles.push_back({q[0], q[2], q[3]});
  }
  return soup;
}

ComparisonRow run_openvdb(const Config& c, const std::string& scene, double h) {
  auto surface = scene_at_start(scene);
  ComparisonRow row{"openvdb", scene, h, c.frames, c.threads};
  std::vector<double> cpu, fill_cpu, wall, survival, triangles;
  std::vector<Vec3> previous;
  for (int k = 0; k <= c.frames; ++k) {
    surface->set_time(static_cast<double>(k) / c.frames);
    const Stopwatch watch;
    const openvdb::FloatGrid::Ptr grid = distance_grid(*surface, h, c.cull);
    const double fill = watch.cpu_seconds();
    TriangleSoup soup = mesh_of(*grid);
    if (k > 0) {  // frame 0 is the initialisation, as for dynamesh
      cpu.push_back(watch.cpu_seconds());
      wall.push_back(watch.wall_seconds());
      fill_cpu.push_back(fill);
      triangles.push_back(static_cast<double>(soup.triangles.size()));
      survival.push_back(position_survival(previous, soup.points));
    }
    if (measured_frame(c, k))
      row.dense_error_max =
          std::max(row.dense_error_max, dense_error(*surface, soup, c.points_per_face, 1 + k));
    previous = std::move(soup.points);
  }
  row.triangles_mean = mean(triangles);
  row.triangles_max = *std::max_element(triangles.begin(), triangles.end());
  row.cpu_seconds_median = median(cpu);
  row.wall_seconds_median = median(wall);
  row.fill_cpu_seconds_median = median(fill_cpu);
  row.survival_mean = mean(survival);
  return row;
}

std::vector<double> number_list(const std::string& option, const std::string& text) {
  std::vector<double> out;
  std::stringstream in(text);
  for (std::string f; std::getline(in, f, ',');) {
    const std::optional<double> x = parse_finite_number(f);
    if (!x || *x <= 0)
      throw std::invalid_argument(option + ": '" + f + "' is not a positive number");
    out.push_back(*x);
  }
  if (out.empty()) throw std::invalid_argument(option + ": empty list");
  return out;
}

Config parse(int argc, char** argv) {
  Config c;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--no-cull") {
      c.cull = false;
      continue;
    }
    if (i + 1 >= argc) throw std::invalid_argument(a + ": unknown option or missing value");
    const std::string v = argv[++i];
    if (a == "--out") {
      c.out = v;
    } else if (a == "--scenes") {
      c.scenes.clear();
      std::stringstream in(v);
      for (std::string s; std::getline(in, s, ',');) c.scenes.push_back(s);
    } else if (a == "--thresholds") {
      c.thresholds = number_list(a, v);
    } else if (a == "--voxels") {
      const std::vector<double> h = number_list(a, v);
      for (auto& [scene, list] : c.voxels) list = h;
    } else if (a == "--frames" || a == "--measure-every" || a == "--points-per-face" ||
               a == "--threads") {
      const std::optional<long long> n = parse_whole_number(v, 1, 100000);
      if (!n) throw std::invalid_argument(a + ": '" + v + "' is not a whole number in [1, 100000]");
      int& target = a == "--frames"          ? c.frames
                    : a == "--measure-every" ? c.measure_every
                    : a == "--threads"       ? c.threads
                                             : c.points_per_face;
      target = static_cast<int>(*n);
    } else {
      throw std::invalid_argument(a + ": unknown option");
    }
  }
  for (const std::string& s : c.scenes)
    if (s != "sphere" && s != "capsule-bend" && s != "twist")
      throw std::invalid_argument("--scenes: '" + s + "' is not sphere, capsule-bend or twist");
  return c;
}

// Triangles and time of OpenVDB at dynamesh's measured error, interpolated log-log between
// the voxel sizes around it, over dynamesh's.
void print_summary(const std::vector<ComparisonRow>& rows) {
  std::cout << "\nscene, T, dense error, triangles dynamesh/openvdb, CPU time dynamesh/openvdb, "
               "survival dynamesh/openvdb\n";
  for (const ComparisonRow& d : rows) {
    if (d.method != "dynamesh") continue;
    std::vector<std::array<double, 2>> tri, sec, surv;
    for (const ComparisonRow& v : rows)
      if (v.method == "openvdb" && v.scene == d.scene) {
        tri.push_back({v.dense_error_max, v.triangles_mean});
        sec.push_back({v.dense_error_max, v.cpu_seconds_median});
        surv.push_back({v.dense_error_max, std::max(v.survival_mean, 1e-9)});
      }
    std::cout << d.scene << ", " << d.parameter << ", " << d.dense_error_max << ", "
              << d.triangles_mean / interpolate_log_log(tri, d.dense_error_max) << ", "
              << d.cpu_seconds_median / interpolate_log_log(sec, d.dense_error_max) << ", "
              << d.survival_mean << " / " << interpolate_log_log(surv, d.dense_error_max) << "\n";
  }
}

int run(const Config& c) {
  openvdb::initialize();
  omp_set_num_threads(c.threads);
  const tbb::global_control tbb_threads(tbb::global_control::max_allowed_parallelism,
                                        static_cast<std::size_t>(c.threads));
  std::vector<ComparisonRow> rows;
  std::ofstream csv(c.out + ".part");
  if (!csv) throw std::runtime_error("cannot write " + c.out + ".part");
  write_csv_header(csv);
  const auto record = [&](const ComparisonRow& r) {
    rows.push_back(r);
    write_csv_row(csv, r);
    csv.flush();
    std::cerr << r.method << ' ' << r.scene << ' ' << r.parameter << ": " << r.triangles_mean
              << " triangles, error " << r.dense_error_max << ", " << 1e3 * r.cpu_seconds_median
              << " ms CPU/frame (" << 1e3 * r.wall_seconds_median << " wall), survival "
              << r.survival_mean << "\n";
  };
  for (const std::string& scene : c.scenes) {
    for (double t : c.thresholds) record(run_dynamesh(c, scene, t));
    for (double h : c.voxels.at(scene)) record(run_openvdb(c, scene, h));
  }
  csv.close();
  if (std::rename((c.out + ".part").c_str(), c.out.c_str()) != 0)
    throw std::runtime_error("cannot rename to " + c.out);
  print_summary(rows);
  return 0;
}

}  // namespace
}  // namespace dynamesh::compare

int main(int argc, char** argv) {
  dynamesh::compare::Config config;
  try {
    config = dynamesh::compare::parse(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "compare_openvdb: " << e.what() << "\n";
    return 2;
  }
  try {
    return dynamesh::compare::run(config);
  } catch (const std::exception& e) {
    std::cerr << "compare_openvdb: " << e.what() << "\n";
    return 1;
  }
}
