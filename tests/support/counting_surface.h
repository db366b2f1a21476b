// CountingSurface: an implicit surface that forwards every call to another one and counts
// the evaluations the adapter asks of it, by kind. For benchmarks that ask how much of a step
// is evaluating the surface (bench_million.cpp): the counts come from a run through this
// wrapper, the cost of each kind from timing the wrapped surface alone, so the atomic counters
// never enter a timing. Tests count with it what an algorithm claims to save
// (test_surface_move.cpp). Forwarding changes no result: every value is the wrapped surface's.
#pragma once

#include <array>
#include <atomic>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "core/surface/surface.h"

namespace dynamesh {

class CountingSurface final : public ImplicitSurface {
 public:
  // What is counted: F alone, F with grad F, the Hessian (with or without F and grad F), and
  // the rest map both ways.
  enum Kind { kValue, kValueGradient, kHessian, kToRest, kFromRest, kKinds };

  explicit CountingSurface(std::unique_ptr<ImplicitSurface> wrapped) : s_(std::move(wrapped)) {
    ImplicitSurface::set_time(s_->time());
  }
  const ImplicitSurface& wrapped() const { return *s_; }
  std::size_t count(Kind k) const { return counts_[k].load(std::memory_order_relaxed); }
  void reset_counts() {
    for (auto& c : counts_) c.store(0, std::memory_order_relaxed);
  }

  std::string name() const override { return s_->name(); }
  void set_time(double t) override {
    ImplicitSurface::set_time(t);
    s_->set_time(t);
  }
  std::vector<SurfaceParameter> parameters() const override { return s_->parameters(); }
  void set_parameter(const std::string& name, double value) override {
    s_->set_parameter(name, value);
  }
  Box3 bounds() const override { return s_->bounds(); }
  double length_scale() const override { return s_->length_scale(); }
  Mesh48 base_mesh() const override { return s_->base_mesh(); }
  double mild_time() const override { return s_->mild_time(); }
  std::vector<std::string> point_quantities() const override { return s_->point_quantities(); }
  double point_quantity(const std::string& name, const Vec3& p) const override {
    return s_->point_quantity(name, p);
  }
  std::shared_ptr<const VolumeImage> volume_image() const override { return s_->volume_image(); }

  double value(const Vec3& p) const override {
    add(kValue);
    return s_->value(p);
  }
  double value_gradient(const Vec3& p, Vec3& gradient) const override {
    add(kValueGradient);
    return s_->value_gradient(p, gradient);
  }
  Mat3 hessian(const Vec3& p) const override {
    add(kHessian);
    return s_->hessian(p);
  }
  double value_gradient_hessian(const Vec3& p, Vec3& gradient, Mat3& hessian) const override {
    add(kHessian);
    return s_->value_gradient_hessian(p, gradient, hessian);
  }
  double difference_step() const override { return s_->difference_step(); }
  bool has_rest_map() const override { return s_->has_rest_map(); }
  bool may_change_topology() const override { return s_->may_change_topology(); }
  Vec3 to_rest(const Vec3& p) const override {
    add(kToRest);
    return s_->to_rest(p);
  }
  Vec3 from_rest(const Vec3& q) const override {
    add(kFromRest);
    return s_->from_rest(q);
  }
  Vec3 invariant_axis() const override { return s_->invariant_axis(); }

 private:
  void add(Kind k) const { counts_[k].fetch_add(1, std::memory_order_relaxed); }
  std::unique_ptr<ImplicitSurface> s_;
  mutable std::array<std::atomic<std::size_t>, kKinds> counts_{};
};

}  // namespace dynamesh
