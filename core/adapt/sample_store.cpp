#include "core/adapt/sample_store.h"

#include <algorithm>
#include <cmath>

#include "core/adapt/error_model.h"
#include "core/mesh/bisection_map.h"
#include "core/parallel.h"

namespace dynamesh {
namespace {

// SplitMix64: a counter-based generator, so a pattern depends only on (seed, pattern number).
std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

double uniform01(std::uint64_t& state) {
  state = mix(state);
  return static_cast<double>(state >> 11) * 0x1.0p-53;
}

double face_area(const Mesh48& mesh, Face f) {
  const auto v = mesh.vertices(f);
  const Vec3& a = mesh.position(v[0]);
  return 0.5 * (mesh.position(v[1]) - a).cross(mesh.position(v[2]) - a).norm();
}

}  // namespace

SampleStore::SampleStore(double density, std::uint64_t seed) : density_(density), seed_(seed) {}

void SampleStore::grow_faces(std::size_t capacity) {
  if (face_head_.size() >= capacity) return;
  face_head_.resize(capacity, kInvalidIndex);
  face_count_.resize(capacity, 0);
  face_error_.resize(capacity, 0.0);
  face_dense_.resize(capacity, 0);
}

void SampleStore::clear_face(std::uint32_t f) {
  for (std::uint32_t s = face_head_[f]; s != kInvalidIndex; s = samples_[s].next)
    free_.push_back(s);
  face_head_[f] = kInvalidIndex;
  face_count_[f] = 0;
}

void SampleStore::push(std::uint32_t f, float b1, float b2, float error) {
  std::uint32_t s;
  if (!free_.empty()) {
    s = free_.back();
    free_.pop_back();
  } else {
    s = static_cast<std::uint32_t>(samples_.size());
    samples_.push_back({});
  }
  samples_[s] = {b1, b2, error, face_head_[f]};
  face_head_[f] = s;
  ++face_count_[f];
  face_error_[f] = std::max(face_error_[f], static_cast<double>(error));
}

std::uint32_t SampleStore::target_count(const Mesh48& mesh, Face f) const {
  const double n = std::round(density_ * face_area(mesh, f));
  return static_cast<std::uint32_t>(std::clamp(n, double{kMinSamplesPerFace}, 1e6));
}

// Stratified: the barycentric triangle is cut into k^2 congruent cells (k(k+1)/2 upright,
// k(k-1)/2 inverted), k^2 >= the target, and one uniformly jittered sample is drawn per cell.
void SampleStore::draw_pattern(const Mesh48& mesh, std::uint32_t f, std::uint32_t min_count) {
  clear_face(f);
  face_error_[f] = 0.0;
  face_dense_[f] = min_count > 0;
  const std::uint32_t n = std::max(target_count(mesh, Face(f)), min_count);
  const auto k = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
  std::uint64_t state = mix(seed_ ^ mix(++patterns_drawn_));
  const double h = 1.0 / k;
  for (int i = 0; i < k; ++i) {
    for (int j = 0; j < k - i; ++j) {
      for (int inverted = 0; inverted < (j < k - i - 1 ? 2 : 1); ++inverted) {
        double r1 = uniform01(state), r2 = uniform01(state);
        if (r1 + r2 > 1) r1 = 1 - r1, r2 = 1 - r2;
        // Cell corner and edge vectors in (b1, b2); the inverted cell is the point reflection.
        const double s = inverted ? -1.0 : 1.0;
        const double c1 = (j + inverted) * h, c2 = (i + inverted) * h;
        push(f, static_cast<float>(c1 + s * r1 * h), static_cast<float>(c2 + s * r2 * h), 0.0f);
      }
    }
  }
}

void SampleStore::reset(const Mesh48& mesh) {
  samples_.clear();
  free_.clear();
  face_head_.assign(mesh.face_capacity(), kInvalidIndex);
  face_count_.assign(mesh.face_capacity(), 0);
  face_error_.assign(mesh.face_capacity(), 0.0);
  face_dense_.assign(mesh.face_capacity(), 0);
  for (Face f : mesh.live_faces()) draw_pattern(mesh, f.idx);
}

bool SampleStore::evaluate_face(const Mesh48& mesh, const SurfaceProbe& probe, Face f) {
  const auto v = mesh.vertices(f);
  const Vec3 p[3] = {mesh.position(v[0]), mesh.position(v[1]), mesh.position(v[2])};
  const Vec2 uv[3] = {mesh.uv(v[0]), mesh.uv(v[1]), mesh.uv(v[2])};
  QuadraticErrorModel model;
  for (std::uint32_t s = face_head_[f.idx]; s != kInvalidIndex; s = samples_[s].next) {
    Sample& x = samples_[s];
    const Vec3 b(1.0 - x.b1 - x.b2, x.b1, x.b2);
    const Vec3 r = probe.residual_at(p, uv, b);
    x.error = static_cast<float>(r.norm());
    model.add(b, r);
  }
  const QuadraticErrorModel::Result r = model.evaluate();
  face_error_[f.idx] = r.error;
  return r.resolved;
}

void SampleStore::evaluate_faces(const Mesh48& mesh, const SurfaceProbe& probe,
                                 const std::vector<Face>& faces) {
  grow_faces(mesh.face_capacity());
  // Member scratch buffers: this runs after every split, so it must not allocate.
  std::vector<Face>& pending = pending_;
  std::vector<Face>& next = next_pending_;
  std::vector<std::uint8_t>& unresolved = unresolved_;
  pending.assign(faces.begin(), faces.end());
  while (!pending.empty()) {
    const auto n = static_cast<std::int64_t>(pending.size());
    unresolved.assign(pending.size(), 0);
#pragma omp parallel for schedule(dynamic, 256) if (n > kParallelMin)
    for (std::int64_t i = 0; i < n; ++i) {
      const Face f = pending[static_cast<std::size_t>(i)];
      if (mesh.is_alive(f))
        unresolved[static_cast<std::size_t>(i)] = !evaluate_face(mesh, probe, f);
    }
    // Densify sequentially (the pool is shared), then measure those faces again.
    next.clear();
    for (std::size_t i = 0; i < pending.size(); ++i) {
      const Face f = pending[i];
      if (!unresolved[i] || face_count_[f.idx] >= kMaxSamplesPerFace) continue;
      draw_pattern(mesh, f.idx, std::min(4 * face_count_[f.idx], kMaxSamplesPerFace));
      next.push_back(f);
    }
    pending.swap(next);
  }
}

void SampleStore::evaluate_all(const Mesh48& mesh, const SurfaceProbe& probe) {
  evaluate_faces(mesh, probe, mesh.live_faces());
}

double SampleStore::weld_error(const Mesh48& mesh, const SurfaceProbe& probe,
                               const DiamondChange& plan, double ceiling) const {
  const auto& pv0 = plan.halves[0].parent_vertices;
  const Vec3 p0[3] = {mesh.position(pv0[0]), mesh.position(pv0[1]), mesh.position(pv0[2])};
  const Vec2 uv0[3] = {mesh.uv(pv0[0]), mesh.uv(pv0[1]), mesh.uv(pv0[2])};
  const double midpoint = probe.error_at(p0, uv0, Vec3(0.0, 0.5, 0.5));
  if (midpoint > ceiling) return midpoint;
  double worst = midpoint;
  for (int h = 0; h < plan.count; ++h) {
    const Bisection& half = plan.halves[h];
    const auto& pv = half.parent_vertices;
    const Vec3 p[3] = {mesh.position(pv[0]), mesh.position(pv[1]), mesh.position(pv[2])};
    const Vec2 uv[3] = {mesh.uv(pv[0]), mesh.uv(pv[1]), mesh.uv(pv[2])};
    QuadraticErrorModel model;
    for (int child = 0; child < 2; ++child) {
      for_each_sample(half.children[child], [&](const Vec3& b, double) {
        const Vec3 pb = to_parent_coordinates(b, child);
        model.add(pb, probe.residual_at(p, uv, pb));
      });
    }
    worst = std::max(worst, model.estimate());
  }
  return worst;
}

std::size_t SampleStore::refresh_patterns(const Mesh48& mesh) {
  std::size_t redrawn = 0;
  for (Face f : mesh.live_faces()) {
    const std::uint32_t target = target_count(mesh, f), n = face_count_[f.idx];
    if (n == 0 || 2 * n < target || (n > 2 * target && !face_dense_[f.idx])) {
      draw_pattern(mesh, f.idx);
      ++redrawn;
    }
  }
  return redrawn;
}

SampleStore::Summary SampleStore::summary(const Mesh48& mesh) const {
  Summary s;
  double sum = 0.0;
  for (Face f : mesh.live_faces()) {
    s.max_error = std::max(s.max_error, face_error_[f.idx]);
    for (std::uint32_t i = face_head_[f.idx]; i != kInvalidIndex; i = samples_[i].next) {
      sum += samples_[i].error;
      ++s.samples;
    }
  }
  s.mean_error = s.samples ? sum / static_cast<double>(s.samples) : 0.0;
  return s;
}

void SampleStore::after_split(Mesh48& mesh, const DiamondChange& change) {
  grow_faces(mesh.face_capacity());
  for (int h = 0; h < change.count; ++h) {
    const Bisection& half = change.halves[h];
    const std::uint32_t parent = half.parent.idx;
    scratch_.clear();
    for (std::uint32_t s = face_head_[parent]; s != kInvalidIndex; s = samples_[s].next)
      scratch_.push_back(s);
    const std::uint32_t child[2] = {half.children[0].idx, half.children[1].idx};
    for (std::uint32_t c : child) {
      face_head_[c] = kInvalidIndex;
      face_count_[c] = 0;
      face_error_[c] = 0.0;
    }
    for (std::uint32_t s : scratch_) {
      Sample& x = samples_[s];
      const Eigen::Vector3f b(1.0f - x.b1 - x.b2, x.b1, x.b2);
      const int which = bisection_child(b);
      const Eigen::Vector3f cb = to_child_coordinates(b, which);
      x.b1 = cb[1];
      x.b2 = cb[2];
      x.next = face_head_[child[which]];
      face_head_[child[which]] = s;
      ++face_count_[child[which]];
    }
    for (std::uint32_t c : child)
      if (face_count_[c] < kMinSamplesPerFace) draw_pattern(mesh, c);
  }
}

void SampleStore::after_weld(Mesh48& mesh, const DiamondChange& change) {
  for (int h = 0; h < change.count; ++h) {
    const Bisection& half = change.halves[h];
    scratch_.clear();
    for (int which = 0; which < 2; ++which) {
      const std::uint32_t c = half.children[which].idx;
      for (std::uint32_t s = face_head_[c]; s != kInvalidIndex; s = samples_[s].next) {
        Sample& x = samples_[s];
        const Eigen::Vector3f pb =
            to_parent_coordinates(Eigen::Vector3f(1.0f - x.b1 - x.b2, x.b1, x.b2), which);
        x.b1 = pb[1];
        x.b2 = pb[2];
        scratch_.push_back(s);
      }
    }
    const std::uint32_t parent = half.parent.idx;
    face_head_[parent] = kInvalidIndex;
    face_count_[parent] = 0;
    face_error_[parent] = 0.0;
    face_head_[half.children[1].idx] = kInvalidIndex;
    face_count_[half.children[1].idx] = 0;
    for (std::uint32_t s : scratch_) {
      samples_[s].next = face_head_[parent];
      face_head_[parent] = s;
      ++face_count_[parent];
    }
    if (face_count_[parent] > 2 * target_count(mesh, half.parent)) draw_pattern(mesh, parent);
  }
}

}  // namespace dynamesh
