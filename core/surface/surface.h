// Surface: the deforming surface S(t) the mesh follows, a black box the adapter can only
// sample (de Goes et al. 2006, Section 3). Two kinds share this interface:
//   - ParametricSurface: S(u, v, t) over a rectangular parameter domain; a mesh vertex
//     carries its (u, v), so bringing it onto the surface is evaluation;
//   - ImplicitSurface: {p : F(p, t) = 0}, F < 0 inside; bringing a point onto the surface
//     is Newton projection along the gradient (core/surface/projection.h).
//
// Contract: set_time() and set_parameter() are called between phases, from one thread;
// every const evaluation method is thread-safe and allocation-free, so millions of samples
// can be evaluated in parallel.
#pragma once

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "core/geometry/vector_types.h"
#include "core/mesh/mesh48.h"

namespace dynamesh {

struct VolumeImage;

// A named, adjustable scalar of a scene (SCENES.md), with its range and a one-line meaning.
struct SurfaceParameter {
  std::string name;
  double value = 0.0;
  double min = 0.0;
  double max = 0.0;
  std::string description;
};

// Principal curvatures k1 >= k2 (signed, positive where the surface bends towards its
// normal's opposite side, i.e. a sphere with outward normal has k = +1/R) and their unit
// directions, with the unit normal; all at one point.
struct PrincipalCurvatures {
  double k1 = 0.0, k2 = 0.0;
  Vec3 dir1{Vec3::UnitX()}, dir2{Vec3::UnitY()};
  Vec3 normal{Vec3::UnitZ()};
};

enum class SurfaceKind { kParametric, kImplicit };

class Surface {
 public:
  virtual ~Surface() = default;

  virtual SurfaceKind kind() const = 0;
  virtual std::string name() const = 0;

  // Animation time, normalised to [0, 1] for the built-in scenes. Cheap to change.
  double time() const { return time_; }
  virtual void set_time(double t) { time_ = t; }

  // Adjustable parameters with current values; set_parameter throws std::invalid_argument
  // for an unknown name or a value outside [min, max].
  virtual std::vector<SurfaceParameter> parameters() const { return {}; }
  virtual void set_parameter(const std::string& name, double value);

  // Bounding box of the surface at the current time (may be conservative).
  virtual Box3 bounds() const = 0;
  // Characteristic length of the scene (finite-difference steps, tolerances): by default
  // the diagonal of bounds().
  virtual double length_scale() const { return bounds().diagonal(); }

  // A coarse 4-8 base mesh with the surface's topology, its vertices on the surface at the
  // current time (parametric: with their (u, v) set).
  virtual Mesh48 base_mesh() const = 0;
  // A time at which the family is mild: its base mesh refines into an embedded mesh, and
  // any other time is reached from it by a motion the adapter follows (Adapter::initialize
  // adapts there and sub-steps to the requested time). NaN (the default): every time is.
  virtual double mild_time() const { return std::numeric_limits<double>::quiet_NaN(); }

  // Scalar quantities the surface carries at its points besides geometry (e.g. the MR
  // intensity of the `mri` scene), by name; the viewer and exporters can colour by them.
  virtual std::vector<std::string> point_quantities() const { return {}; }
  // NaN for an unknown name. Thread-safe like every const evaluation.
  virtual double point_quantity(const std::string& name, const Vec3& p) const;
  // The scan behind a volume scene (mri): intensities with their placement and an optional
  // label atlas, for per-fragment colouring and picking (volume_image.h); null otherwise.
  virtual std::shared_ptr<const VolumeImage> volume_image() const { return nullptr; }

 private:
  double time_ = 0.0;
};

// Value and derivatives of S(u, v) at one parameter point.
struct ParametricDerivatives {
  Vec3 s, su, sv, suu, suv, svv;
};

// Rectangular parameter domain [min, max]; a periodic direction wraps.
struct ParameterDomain {
  Vec2 min{Vec2::Zero()}, max{Vec2::Ones()};
  bool periodic_u = false, periodic_v = false;
};

class ParametricSurface : public Surface {
 public:
  SurfaceKind kind() const final { return SurfaceKind::kParametric; }

  virtual ParameterDomain domain() const = 0;
  virtual Vec3 position(const Vec2& uv) const = 0;
  // Periodic directions: the copy of uv (shifted by whole periods) nearest to `reference`, so
  // that interpolation across the seam stays continuous; identity for non-periodic ones.
  Vec2 unwrap_near(const Vec2& uv, const Vec2& reference) const;
  // uv brought into the domain: wrapped along periodic directions, clamped along others.
  Vec2 wrap_into_domain(const Vec2& uv) const;
  // Analytic where a closed form exists; by default central differences with a step taken
  // from the domain's size.
  virtual ParametricDerivatives derivatives(const Vec2& uv) const;
  // Unit normal Su x Sv / |Su x Sv|.
  Vec3 normal(const Vec2& uv) const;
  // From the first and second fundamental forms.
  PrincipalCurvatures curvatures(const Vec2& uv) const;
};

class ImplicitSurface : public Surface {
 public:
  SurfaceKind kind() const final { return SurfaceKind::kImplicit; }

  virtual double value(const Vec3& p) const = 0;
  // F and grad F together (cheaper for most scenes); by default central differences.
  virtual double value_gradient(const Vec3& p, Vec3& gradient) const;
  // By default central differences of value_gradient().
  virtual Mat3 hessian(const Vec3& p) const;
  // F, grad F and Hess F together; by default value_gradient() and hessian(). Scenes that get
  // all three from one evaluation (a rest shape under a map, jet.h) override it: curvatures()
  // needs all three, once per vertex per step (issue 17's profile: a third of the smoothing).
  virtual double value_gradient_hessian(const Vec3& p, Vec3& gradient, Mat3& hessian) const;
  // Finite-difference step used by the defaults above; from length_scale().
  virtual double difference_step() const { return 1e-5 * length_scale(); }

  // Principal curvatures from the gradient and Hessian (Goldman 2005), normal = grad/|grad|.
  PrincipalCurvatures curvatures(const Vec3& p) const;

  // Material transport, for surfaces that are a rest shape under a known deformation: the
  // rest-space point of a world point at the current time, and back. The adapter carries its
  // vertices through rest space from one step to the next so that they follow the material
  // (with correction along the normal only, a rotating cap slides under its vertices, and
  // the mesh must refine anew behind every moving feature). Without a map, vertices are
  // corrected along the normal only.
  virtual bool has_rest_map() const { return false; }

  // True when F's zero set may merge, split or pinch over time and base_mesh() rebuilds a mesh
  // of whatever topology F has at the current time (a contoured base mesh): the adapter then
  // watches F's critical points each step and rebuilds the mesh at an event (issue 16).
  virtual bool may_change_topology() const { return false; }
  virtual Vec3 to_rest(const Vec3& p) const { return p; }
  virtual Vec3 from_rest(const Vec3& q) const { return q; }

  // A unit axis along which the family never moves its points (zero: none): every point stays
  // in its plane normal to the axis over all times (twist: each cross-section turns within its
  // plane). Tangential smoothing then keeps each vertex's coordinate along the axis
  // (tangential_smoothing.h), so that smoothing on the deformed surface cannot carry vertices
  // along a direction in which the surface itself never moves.
  virtual Vec3 invariant_axis() const { return Vec3::Zero(); }
};

}  // namespace dynamesh
