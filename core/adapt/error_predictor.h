// ErrorPredictor: which faces a step must measure (predictive sampling, issue 17).
//
// Measuring every sample every step costs at least one surface evaluation per sample, most of
// a step. Yet on a smooth animation most faces' errors barely change between steps: what
// changes a face's error is not how far it moves but how the surface bends under it
// differently than before. The predictor keeps, per face, what that bending was when the
// face was last measured, and re-measures only faces whose error could since have left the
// range in which no decision depends on it.
//
// The bound. Over a triangle with vertices p_i on the surface, the residual (implicit: the
// signed distance of the flat triangle's point; parametric: x(b) - S(uv(b))) vanishes at the
// corners; along the edge from p_i to p_j (t = b_j) its slopes at the ends are what the
// vertices' first-order data give:
//   implicit   r'(0) = (p_j - p_i) . n_i,  r'(1) = (p_j - p_i) . n_j   (n: unit normals)
//   parametric r'(0) = (p_j - p_i) - J_i (uv_j - uv_i),  likewise J_j  (J = [S_u S_v])
// so that to third order
//   r(b) = sum_{i<j} b_i b_j (c_ij + d_ij (b_j - b_i)) + e b_0 b_1 b_2,
//   c_ij = (r'(0) - r'(1)) / 2,  d_ij = -(r'(0) + r'(1)) / 2:
// c_ij is half the surface's second derivative along the edge, averaged over it (the
// quadratic model's coefficient, error_model.h), d_ij how that second derivative changes
// along the edge. Between the face's last measurement and now, the error can therefore have
// changed by at most
//   max |sum b_i b_j dc_ij| + min(max |dd| 0.1176, sum |dd| / (6 sqrt 3)),
// dc, dd the changes of the coefficients. The first maximum is over the triangle: exact where
// the residual is scalar (implicit: scalar_maximum, error_model.h), else
// min(max |dc| / 3, sum |dc| / 4) (the maxima of sum b_i b_j and of b_i b_j); the second comes
// from the maxima of sum b_i b_j |b_j - b_i| and of one such term. This covers every cause the
// step knows of — the vertices' normal correction and tangential moves (through p and uv), the
// surface's own motion (through the normals and Jacobians at the vertices' new places), and how
// that motion varies across the face (a rigid motion of a face with its surface leaves c and d
// unchanged, however fast). The cubic term is needed where a face slides across a change of
// curvature (twist's rounded rims, where smoothing moves vertices around the section): there d
// flips sign while c barely changes, and the sampled reading of a skipped face moved by 1.4x a
// bound without d (PredictiveAnimation/twist, T = 0.002).
//
// Assumptions, and what guards them:
//   - The residual is cubic over the triangle. Faces where the quadratic model did not fit
//     their samples (SampleStore::densified) are always measured, and the bound is multiplied
//     by a safety factor (kSafety, error_predictor.cpp) for the term e the vertices do not
//     see, the higher terms, and how the sampled estimate (a least-squares fit, error_model.h)
//     responds to them; and by SampleStore::reading_gain where the reading ramps in its edge
//     peaks (near the split bound).
//   - The vertices lie on the surface (normal correction). Where a projection left a vertex
//     off it, that vertex's distance to the surface is added to the bound (the residual is
//     then no longer zero there; it moves the face's error by at most that much).
//   - The change since the reference is small against the scale on which the surface's shape
//     changes, so that every term of the residual (those the vertices see and those they do
//     not) changed linearly in the face's displacement s relative to the surface, and the
//     ratio of the unseen to the seen changes is the ratio of the surface's derivatives at
//     the face, which kSafety covers (calibrated: error_predictor.cpp). The remainder of that
//     linearisation is of relative size s / L, L the length over which the surface's derivatives
//     change; for a surface smooth at the scale of its curvature radius, L ~ rho. The triangle's
//     size h does not enter: it sets each term's size (h^2 c'', h^3 d'', h^3 e, h^4 ...) alike now
//     and at the reference. So a face is measured when its corners' summed moves since its
//     reference measurement exceed kMaxTravelFraction of the smallest curvature radius the
//     mesh's vertex normals show this step (curvature_radius(): one number for the whole mesh,
//     so that no flat face is trusted next to a curved region sliding towards it). This is
//     what catches a sudden jump in time. (A guard comparing one step's move with a quarter
//     of the face's shortest edge, as this one once was: at 10^6 triangles a step's motion tripped
//     it for 55% of the faces, though it moved them by ~1% of the curvature radius.)
//   - Where the surface's curvature jumps (a C1 seam: the capsule's cylinder meeting its
//     caps) the shape changes over no length at all: neither the linearisation above nor the
//     corners' data need see what happens inside the face. Two things change the residual
//     there. (a) The face stretching across the seam: a face whose edges changed by a factor
//     within 1 +- s since its reference reads up to (1 + s)^2 of its error on the same
//     curvatures, so 2 s times its last error is added to the bound where the vertices were
//     carried with the material this step (kStrainGain, error_predictor.cpp). Without it,
//     capsule-bend's skipped faces on the inner side of its seams used 0.99 of their bound
//     (PredictiveAnimation, T = 0.002), with it 0.25. (b) A seam sliding across the face changes
//     its residual by ~ (slide / h) of its size: a face with a corner that slid over the surface by
//     more than kMaxSlideFraction of its shortest edge this step is measured (on the slide, not
//     the whole move). The slide is the move relative to the surface's material
//     where the surface has a rest map (capsule-bend: the vertices are carried with it, and only
//     the correction and the smoothing slide them; the seam stays under the same faces), else the
//     whole move.
//   - Stochastic sampling and drift beyond all of the above: every face is measured on its turn
//     in the rotation (SampleStore::on_turn, 1/kRotation of the faces every step), so no face
//     goes unmeasured for more than kRotation steps.
// Faces whose samples changed (split, weld, new pattern: SampleStore::measured() false) are
// always measured. Those two kinds of measurement, which full sampling makes too, are the only
// ones at which a face's interior peak is looked for (SampleStore::peak_check_due), so that both
// modes keep the same samples without prediction measuring a face for that alone. (Looked for at
// every measurement, with nothing making prediction measure, sinc at T = 0.002 parted from full
// sampling at step 59 of 100 and twist at step 14 of 40, PredictiveDecisions. Looked for at the
// first measurement reading in the search band, prediction had to measure every face that
// could cross into it: ~650 of the ~2,730 faces measured per twist step at T = 1e-3.)
//
// A face is then skipped only when no criterion could ask to split it at the top of its
// reading's range (split_urgency is non-decreasing in the error): the reading it would have
// with its model reading and its edge peaks each raised by the bound's residual part
// (reading_range; never above its last error plus the bound, and below it where the model is
// the reading and the peaks count only through the ramp: with the top at last error plus
// bound, half the twist's faces measured for the split bound at T = 1e-3 were such faces).
// Weld decisions measure the post-weld error themselves; where a star's current error (the
// "no gain" rule, criteria.h) could decide differently anywhere inside its faces' ranges, the
// adapter measures those faces first (star_error_range). Split and weld decisions are
// therefore those of full sampling as long as the assumptions hold; which faces are measured,
// and so the skipped faces' stale readings, are not.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

#include "core/adapt/sample_store.h"
#include "core/adapt/surface_probe.h"
#include "core/mesh/mesh48.h"
#include "core/parallel.h"
#include "core/surface/projection.h"

namespace dynamesh {

class ErrorPredictor final : public MeshListener {
 public:
  // A face whose corners travelled more than this fraction of curvature_radius() since its
  // reference measurement is measured (the header's "Assumptions").
  static constexpr double kMaxTravelFraction = 0.25;
  // A face one of whose corners slid over the surface by more than this fraction of its
  // shortest edge this step is measured (the header's "Assumptions": curvature jumps).
  static constexpr double kMaxSlideFraction = 0.25;
  // The rotation's length (its turns are the samples': SampleStore::on_turn).
  static constexpr std::uint32_t kRotation = SampleStore::kRotation;

  // Forgets every face's reference (e.g. when switching from full sampling).
  void invalidate();

  // Start of a step's sampling, after the geometric correction: the vertices' first-order
  // data at their new places. `start_positions` are the positions at the start of the step;
  // `material_positions` (surfaces with a rest map, else null), where each vertex's material
  // point from the start of the step is now: a vertex's slide over the surface is its
  // distance from it (without one, its whole move counts as slide).
  // Implicit surfaces: a vertex that still sits exactly where note() saw F and grad F
  // evaluated, in the surface state `epoch`, reuses them (the same numbers an evaluation
  // would give: exact).
  void begin_step(const Mesh48& mesh, const SurfaceProbe& probe,
                  const std::vector<Vec3>& start_positions, std::uint64_t step,
                  std::uint64_t epoch = 0, const std::vector<Vec3>* material_positions = nullptr);

  // F and grad F were evaluated at `point` (where vertex v now is) in the surface state
  // `epoch` (> 0), e.g. by the projection that put it there. Thread-safe for distinct
  // vertices; call grow_for(mesh) first.
  void note(Vertex v, const Vec3& point, double value, const Vec3& gradient, std::uint64_t epoch) {
    evaluated_[v.idx] = PointEvaluation{point, value, gradient, epoch};
  }
  void grow_for(const Mesh48& mesh) { grow(mesh); }
  // What note() kept, by vertex id (the smoothing starts its moves from them too:
  // SmoothingOptions::evaluations).
  const std::vector<PointEvaluation>& evaluations() const { return evaluated_; }

  // Whether some criterion would split face f at an error. `asks` is called only above
  // `floor`, an error at or below which none would (Adapter::split_error_floor): most skipped
  // faces of an adapted mesh read below it, and are judged without a call.
  struct SplitTest {
    double floor = -std::numeric_limits<double>::infinity();
    std::function<bool(Face, double)> asks;
    bool operator()(Face f, double error) const { return error > floor && asks(f, error); }
  };
  // The faces to measure this step. Stores every skipped face's bound (bound()). `samples`
  // names the step begin_step() was given (SampleStore::set_step): the faces on their turn are
  // measured.
  void select(const Mesh48& mesh, const SurfaceProbe& probe, const SampleStore& samples,
              const SplitTest& would_split, std::vector<Face>& measure);

  // After faces were measured: records their reference coefficients (their bound is 0).
  void record(const Mesh48& mesh, const SurfaceProbe& probe, const std::vector<Face>& faces);

  // How far the face's true error may be from SampleStore::face_error this step: 0 for a face
  // measured this step (or whose samples changed since, which face_error reports as 0, as
  // with full sampling).
  double bound(const SampleStore& samples, Face f) const {
    return f.idx < bound_.size() && samples.measured(f) ? bound_[f.idx] : 0.0;
  }
  // Where the face's true reading may be this step: within bound() of face_error, and within
  // the readings at its model reading and edge peaks moved by the bound's residual part
  // (SampleStore::reading_upper, reading_lower), often a narrower range where the reading ramps
  // in its peaks. [face_error, face_error] where bound() is 0.
  struct Range {
    double lo, hi;
  };
  Range reading_range(const SampleStore& samples, Face f) const {
    const double e = samples.face_error(f), b = bound(samples, f);
    if (!(b > 0.0)) return {e - b, e + b};
    return {std::max(e - b, samples.reading_lower(f, rise_[f.idx])),
            std::min(e + b, samples.reading_upper(f, rise_[f.idx]))};
  }

  std::size_t skipped() const { return skipped_; }
  // Faces the last select() measured only because their corners travelled or slid too far.
  std::size_t guarded() const { return guarded_; }
  // The smallest curvature radius the last select() saw: over every face, the shortest edge
  // length over the turn of the unit normal between its ends (a chord estimate of 1/|k_n|).
  double curvature_radius() const { return curvature_radius_; }
  // Vertices whose F and grad F the last begin_step took from note() instead of evaluating.
  std::size_t reused_evaluations() const { return reused_evaluations_; }

  // A split-born vertex (its id may be one a weld freed this step) has no frame yet.
  void after_split(Mesh48& mesh, const DiamondChange& change) override;
  void after_weld(Mesh48&, const DiamondChange&) override {}
  // Every face's reference, every vertex's frame move to the new ids.
  void after_renumber(Mesh48& mesh, const Renumbering& renumbering) override;

 private:
  // First-order data of a vertex. `normal`: the unit normal (implicit: grad F / |grad F|, what
  // the residual's slopes read; both kinds: the curvature radius' estimate). `offset`: the
  // vertex's distance to the surface (implicit, first order; 0 parametric). Parametric surfaces
  // also need S_u and S_v (Tangents), kept apart: select() reads every face's three corners'
  // frames each step, and with the tangents in them a frame took 80 bytes instead of 32 (at 10^6
  // triangles 38 MB, more than this machine's 32 MB cache, instead of 15).
  struct VertexFrame {
    Vec3 normal{Vec3::Zero()};
    double offset = 0.0;
  };
  struct Tangents {
    Vec3 su{Vec3::Zero()}, sv{Vec3::Zero()};
  };
  struct Coefficients {
    // Per edge (opposite vertex i) the coefficient vectors (implicit: [i][0]) of the residual
    // along it, r(t) = t (1 - t) (c + d (2 t - 1)): c quadratic, d cubic.
    float c[3][3];
    float d[3][3];
    float length[3];  // the edges' lengths (the face's strain since its reference)
  };
  // A face's reference on an implicit surface, whose residual is scalar: the coefficients'
  // first components (36 bytes instead of 84; select() reads every skipped face's each step).
  struct ScalarCoefficients {
    float c[3], d[3], length[3];
  };

  void grow(const Mesh48& mesh);
  // Keeps S_u and S_v per vertex and the coefficient vectors per face from the first parametric
  // surface on (implicit ones read neither).
  void keep_parametric_data(const SurfaceProbe& probe);
  void refresh_vertex(const Mesh48& mesh, const SurfaceProbe& probe, Vertex v,
                      std::uint64_t epoch = 0);
  Coefficients coefficients(const Mesh48& mesh, const SurfaceProbe& probe, Face f) const;
  // The same from the face's corners and edges (edge e from corner e + 1 to corner e + 2).
  Coefficients coefficients(const Mesh48& mesh, const SurfaceProbe& probe,
                            const std::array<Vertex, 3>& v, const Vec3 (&edges)[3]) const;

  std::uint64_t step_ = 0;
  std::vector<VertexFrame> frame_;
  std::vector<Tangents> tangents_;  // parametric surfaces only (keep_parametric_data)
  bool parametric_ = false;
  std::vector<std::uint64_t> frame_step_;   // step each frame was computed at (+1; 0 = never)
  std::vector<Vertex> unframed_;            // record()'s scratch: vertices without a frame
  std::vector<float> moved_;                // each vertex's displacement this step
  std::vector<float> slid_;                 // and its slide over the surface (begin_step)
  std::vector<PointEvaluation> evaluated_;  // note()
  std::size_t reused_evaluations_ = 0;
  std::vector<ScalarCoefficients> reference_;   // implicit surfaces
  std::vector<Coefficients> vector_reference_;  // parametric surfaces (keep_parametric_data)
  std::vector<std::uint8_t> has_reference_;
  std::vector<double> bound_;
  std::vector<double> rise_;  // bound_ before SampleStore::reading_gain (reading_range)
  // Per face, its corners' largest summed move since its reference measurement (an upper
  // bound of how far any corner got from where it was then).
  std::vector<float> travel_;
  std::vector<std::uint8_t> flags_;   // select's scratch
  OrderedCollector<Face> collector_;  // select's list of faces to measure, in face order
  std::size_t skipped_ = 0, guarded_ = 0;
  double curvature_radius_ = std::numeric_limits<double>::infinity();
  bool carried_ = false;  // begin_step had the material positions (the strain term applies)
  // Each of the last kRotation steps' smallest radius (by step % kRotation).
  std::array<double, kRotation> radius_ = filled_radii();
  static std::array<double, kRotation> filled_radii() {
    std::array<double, kRotation> r;
    r.fill(std::numeric_limits<double>::infinity());
    return r;
  }
};

}  // namespace dynamesh
