// The adapter's topology hooks (issue 16): kept apart from the per-step phases in adapter.cpp.
#include <algorithm>
#include <chrono>
#include <exception>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/adapt/adapter.h"
#include "core/geometry/fold_repair.h"
#include "core/topology/component_repair.h"
#include "core/topology/contour_base_mesh.h"
#include "core/topology/face_crossings.h"
#include "core/topology/local_repair.h"
#include "core/topology/marching_tetrahedra.h"
#include "core/topology/topology_events.h"

namespace dynamesh {
namespace {

// The cut reaches two cells of the watching grid around the critical point (the mesh is wrong
// within about one: the event happened since the last step), the patch is contoured at the
// seam's edge size, between half a cell and three quarters of one (local_repair.h; a whole
// cell left the narrow blobs' new neck faces so large that their sparse samples missed the
// error next to it: dense error 1.11 (T + eps) in the step after the merge).
// The repair's splits put their vertices where the adapter's tracker will when they are made
// on the mesh (Tracker::after_split): the repair plans on those positions (local_repair.h).
LocalRepairOptions local_repair_options(const TopologyMonitor& monitor, const SurfaceProbe& probe) {
  const double cell = monitor.spacing();
  LocalRepairOptions o;
  o.fill_cut = monitor.fixed_points() != nullptr;  // a layer of a distance field
  o.radius = 2.0 * cell;
  o.spacing = 0.5 * cell;
  o.max_spacing = 0.75 * cell;
  o.place_split_vertex = [&probe](Mesh48& mesh, const DiamondChange& change) {
    probe.put_split_vertex(mesh, change);
  };
  return o;
}

}  // namespace

void Adapter::watch_topology() {
  topology_.reset();
  const auto* implicit = dynamic_cast<const ImplicitSurface*>(&surface_);
  if (!options_.topology_events || !implicit || !implicit->may_change_topology()) return;
  topology_ = std::make_unique<TopologyMonitor>(ContourBaseOptions{}, options_.threshold);
  topology_->reset(*implicit, mesh_);
  // Fixed critical points none of which matters at T (mri with its sulci closed): the surface
  // keeps its topology, and the run what it was without a monitor.
  if (topology_->idle()) topology_.reset();
}

void Adapter::check_topology() {
  const auto& implicit = dynamic_cast<const ImplicitSurface&>(surface_);
  const TopologyCheck check = topology_->check(implicit);  // once per sub-step
  stats_.topology_events.insert(stats_.topology_events.end(), check.events.begin(),
                                check.events.end());
  stats_.topology_seconds += check.seconds;
  note_singular_points();
  if (!check.rebase) return;
  // Locally first; when that cannot be done the whole mesh is rebuilt from F's contour at this
  // time (a global re-base), which the split pass then refines like a first mesh.
  const auto start = std::chrono::steady_clock::now();
  // Until the step ends, splits next to the new neck or tips are kept from folding
  // (SurfaceProbe::project_split_vertex): the mesh there is coarse against a feature that
  // grows from zero.
  probe_.set_split_fold_guard(true);
  if (!repair_topology_locally(check)) {
    // What the mesh must become (topology_events.h): the trusted contour's topology, else the
    // Euler characteristic Morse theory gives.
    const bool rebuilt = check.contour_trusted
                             ? rebuild_or_keep(check.contour.euler, check.contour.components)
                             : rebuild_or_keep(check.expected_euler, 0);
    stats_.rebuilt |= rebuilt;
    // A mesh kept as it was (a distance field's layer) has no new neck or tips to guard, and
    // the guard is not local: it keeps every split of the step off F where the split would fold
    // a face, and a brain layer has such places all over its folds. On Colin27 with closing 2
    // the hole opening 0.8 mm deep left 25 split vertices off F in that step, and the next step
    // planned 32 sub-steps (strain 45, against 12 and 2.8 without a monitor) and took 2.3 times
    // as long (test MriEvents.Colin27HoleNotRepairedLeavesTheStepAsWithoutAMonitor).
    if (!stats_.rebuilt && stats_.local_repairs == 0) {
      probe_.set_split_fold_guard(false);
      hold_splits();
    }
  }
  topology_->mesh_rebuilt(mesh_);
  stats_.topology_seconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void Adapter::note_singular_points() {
  // A distance field's layer (fixed critical points) is left as it was: its critical points
  // are many, and |grad D| = 1 almost everywhere makes its first-order distance exact.
  std::vector<Vec3> points;
  if (!topology_->fixed_points()) {
    for (const CriticalPoint& c : topology_->critical_points()) {
      if (!(c.curvature > 0.0)) continue;
      // The level set F = 0 passes within this of the point (a neck's or a gap's half width).
      const double waist = std::sqrt(2.0 * std::abs(c.value) / c.curvature);
      // Wider than the watching grid's cells, it bends no more sharply than the faces there,
      // finer than those cells, already follow.
      if (waist < 2.0 * topology_->spacing()) points.push_back(c.position);
    }
  }
  probe_.set_singular_points(points);
}

bool Adapter::repair_topology_locally(const TopologyCheck& check) {
  if (!options_.local_topology_repair) return false;
  const auto& implicit = dynamic_cast<const ImplicitSurface&>(surface_);
  LocalRepairOptions o = local_repair_options(*topology_, probe_);
  // An event on a step time (F's critical point zero to within rounding) is repaired at that
  // very instant, where the patch's grid cannot tell the two sides of the critical point apart
  // (local_repair.h): where no patch of F = 0 would do, the patch is contoured off zero, by a
  // quarter of the grid's resolution bound as the re-base's first level (mid_run_base_mesh).
  // The torus pinched at 135 degrees on a frame (t = 0.3, 10 steps): the points of the patch's
  // grid beside the pinch read F = -7e-4 (inside), the grid's face diagonals joining them pass
  // the pinch along the tube, F = +2e-3 at their middles, and the contour kept the tube joined
  // through flat triangles; every attempt was refused and the whole mesh rebuilt (survival
  // 0.897).
  constexpr double kClearFraction = 0.25;
  o.contour_level = [this](const Box3& box, double diagonal) {
    return topology_->clear_level(diagonal, kClearFraction, &box).value_or(0.0);
  };
  std::size_t repaired = 0;
  for (const TopologyEvent& e : check.events) {
    if (e.kind == TopologyEventKind::kMismatch) {
      stats_.repair_refusals.push_back(
          "the contour's topology differs from the mesh's, but no critical point of F crossed "
          "zero: the change is not located");
      return false;
    }
    // A component born or dying touches no other part of the mesh (component_repair.h).
    const LocalRepairResult r = e.kind == TopologyEventKind::kBirth
                                    ? add_born_component(mesh_, implicit, e.position, o)
                                : e.kind == TopologyEventKind::kDeath
                                    ? remove_dead_component(mesh_, implicit, e.position, o)
                                    : repair_locally(mesh_, implicit, e.position, o);
    if (!r.repaired) {
      stats_.repair_refusals.push_back(r.why_not);
      continue;
    }
    ++repaired;
    repair_centres_.push_back(e.position);
    stats_.repair_faces_replaced += r.removed_faces;
    stats_.repair_spacing = std::max(stats_.repair_spacing, r.spacing);
    adopt_repair(r.new_vertices);
  }
  if (repaired == 0) return false;
  stats_.local_repairs += repaired;
  // What the mesh must be now: the grid's contour where it resolves F's critical points, else
  // the Euler characteristic Morse theory gives for the events (topology_events.h).
  const MeshTopologySummary now = summarize_topology(mesh_);
  const bool right =
      check.contour_trusted ? now == check.contour : now.euler == check.expected_euler;
  if (!right)
    stats_.repair_refusals.push_back(
        "the repaired mesh has Euler characteristic " + std::to_string(now.euler) + " and " +
        std::to_string(now.components) + " component(s), F's zero set " +
        (check.contour_trusted ? std::to_string(check.contour.euler) + " and " +
                                     std::to_string(check.contour.components)
                               : std::to_string(check.expected_euler) + " (Morse)"));
  return right;
}

namespace {

// check_orientation's test for a mesh made mid-run: every face facing up F's gradient.
bool faces_outwards(const Mesh48& mesh, const ImplicitSurface& surface) {
  for (const Face f : mesh.live_faces()) {
    const auto v = mesh.vertices(f);
    const Vec3 &a = mesh.position(v[0]), &b = mesh.position(v[1]), &c = mesh.position(v[2]);
    Vec3 g;
    surface.value_gradient((a + b + c) / 3.0, g);
    if (!((b - a).cross(c - a).dot(g) > 0)) return false;
  }
  return true;
}

}  // namespace

bool Adapter::rebuild_or_keep(long euler, long components) {
  if (!topology_->fixed_points()) {
    rebuild_from_base(euler, components);
    return true;
  }
  // A distance field's layer is rebuilt only where a contour has the topology it must take
  // (mid_run_base_mesh), else kept. The dumbbell after motion9, before its local repair was
  // mended (raise_border in local_repair.cpp): rebuilt at its split, 2,936 triangles and an
  // error of 0.03 to 0.06 mm after. On Colin27 with closing 2 the hole opening 0.8 mm deep has
  // no such contour (test MriEvents.Colin27HoleNotRepairedLeavesTheStepAsWithoutAMonitor); the
  // re-base to the old Euler characteristic, tried once, left 2,828 faces folded.
  std::string why = "no global re-base (not asked for)";
  if (options_.topology_rebase) {
    try {
      rebuild_from_base(euler, components);
      return true;
    } catch (const std::invalid_argument& e) {
      why = std::string("no global re-base: ") + e.what();
    }
  }
  stats_.repair_refusals.push_back(why + "; the mesh keeps its topology");
  return false;
}

void Adapter::hold_splits(const std::string& stalled) {
  // After an event only when the options say so; for a stalled face once (the first such face
  // sets the depth; split_pass holds each stalled face itself).
  if (stalled.empty() ? !options_.hold_splits_when_unrepaired : held_depth_ >= 0) return;
  // A mesh that keeps a topology F no longer has cannot meet the bound where they differ: the
  // split queue refined without end towards a surface the mesh cannot reach (the dumbbell's
  // split after motion9, unrepaired: more than 13 minutes, 1.5 GB, and still in step 3; Colin27
  // with closing 2 at 4 mm deep, with or without a monitor: 522,000 triangles). So from then
  // on no face deeper than kHeldLevels bisections below the deepest face now is split (two
  // bisections halve an edge): the refinement ends, the error where the mesh is wrong stays
  // above T and is reported (the step's max error; splits_held, on stderr).
  constexpr int kHeldLevels = 4;
  int deepest = 0;
  for (const Face f : mesh_.live_faces()) deepest = std::max(deepest, mesh_.depth(f));
  if (held_depth_ < 0) held_depth_ = deepest + kHeldLevels;
  const std::string from_now = "from now on no face is split beyond depth " +
                               std::to_string(held_depth_) + " (the deepest now is " +
                               std::to_string(deepest) + ")";
  stats_.repair_refusals.push_back(
      stalled.empty() ? from_now +
                            ": where the mesh's topology is not F's the refinement would not "
                            "end, and the error there stays above T"
                      : stalled + ", and " + from_now);
}

Mesh48 Adapter::mid_run_base_mesh(long euler, long components) {
  // The surface's own base mesh first (a contour of F on its grid). Right at an event F has a
  // double cone (grad F = 0 on the surface) and the contour's triangles at the cone's tip can
  // face against grad F: the surface refuses such a base (check_orientation). That is often a
  // fact about where the grid's points fall, not about the surface: contours on slightly
  // different grids (other cell counts along the longest side, so that no grid point keeps its
  // place near the tip) are tried. When every grid folds, the surface is one no mesh can
  // follow (ripples finer than the grid: CliHostile), and the surface's refusal stands.
  // A base is taken only with the topology asked for. Just after an event the grid's
  // piecewise-linear contour may still join two tips closer than a cell (or miss a new neck
  // thinner than one); refining such a base cannot make it right: the split queue bridged the
  // gap between the tips with ever more triangles, up to the triangle budget (the wide blobs'
  // split, issue 16). Then F = level is contoured, the level moved off zero just far enough
  // that the grid resolves every critical point on its own side (TopologyMonitor::clear_level),
  // and the vertices are projected onto F = 0.
  const auto wanted = [&](const Mesh48& mesh) {
    const MeshTopologySummary s = summarize_topology(mesh);
    return s.euler == euler && (components == 0 || s.components == components);
  };
  std::exception_ptr refusal;
  try {
    Mesh48 mesh = surface_.base_mesh();
    if (wanted(mesh)) return mesh;
  } catch (const std::invalid_argument&) {
    refusal = std::current_exception();
  }
  const auto* implicit = dynamic_cast<const ImplicitSurface*>(&surface_);
  bool outwards = false;
  for (const double fraction : {0.0, 0.25, 0.5, 1.0}) {
    if (!implicit || (fraction > 0 && !topology_)) break;
    for (const int cells : {25, 23, 27, 21, 29, 20}) {
      ContourBaseOptions o;
      o.cells_along_longest = cells;
      if (fraction > 0) {
        const Box3 box = implicit->bounds();
        const double diagonal =
            make_contour_grid(box, box.size().maxCoeff() / cells).spacing().norm();
        const std::optional<double> level = topology_->clear_level(diagonal, fraction);
        if (!level || *level == 0.0) continue;  // none, or the plain contour tried already
        o.level = *level;
      }
      try {
        Mesh48 mesh = make_contour_base_mesh(*implicit, o);
        if (!faces_outwards(mesh, *implicit)) continue;
        outwards = true;
        if (wanted(mesh)) return mesh;
      } catch (const std::invalid_argument&) {
      }
    }
  }
  if (refusal && !outwards) std::rethrow_exception(refusal);
  throw std::invalid_argument(
      surface_.name() + ": at t=" + std::to_string(surface_.time()) +
      " no contour of F on any grid has the topology the mesh must take (Euler characteristic " +
      std::to_string(euler) +
      (components > 0 ? ", " + std::to_string(components) + " component(s)" : std::string()) +
      "), so the mesh cannot be rebuilt there");
}

namespace {

// Where a fold is, for grouping folds into patches.
Vec3 face_corner_mean(const Mesh48& mesh, Face f) {
  Vec3 c = Vec3::Zero();
  for (const Vertex v : mesh.vertices(f)) c += mesh.position(v);
  return c / 3.0;
}

// Where to re-mesh the folds: the mean of all their corners when every corner lies within
// `reach` of it (one patch for them all); else the mean of the corners of the folds near the
// first one (within `reach` of its corners' mean) when those lie within `reach` of it; else
// the first fold's own corner mean when its corners lie within twice `reach` (the cut's
// radius: a large face alone, such as a strip triangle where an earlier patch met the seam;
// the three blobs in a row, 40 steps: one at 0.37 from the neck, 0.22 across, and the mesh was
// rebuilt); else nothing (folds spread too widely for patches).
std::optional<Vec3> fold_cluster_centre(const Mesh48& mesh, const std::vector<Face>& folded,
                                        double reach) {
  const auto centre_of = [&](auto&& member) -> std::optional<Vec3> {
    Vec3 centre = Vec3::Zero();
    std::size_t faces = 0;
    for (const Face f : folded)
      if (member(f)) centre += face_corner_mean(mesh, f), ++faces;
    centre /= static_cast<double>(faces);
    for (const Face f : folded)
      if (member(f))
        for (const Vertex v : mesh.vertices(f))
          if ((mesh.position(v) - centre).norm() > reach) return std::nullopt;
    return centre;
  };
  if (const auto all = centre_of([](Face) { return true; })) return all;
  const Vec3 seed = face_corner_mean(mesh, folded.front());
  if (const auto near =
          centre_of([&](Face f) { return (face_corner_mean(mesh, f) - seed).norm() <= reach; }))
    return near;
  reach *= 2.0;
  return centre_of([&](Face f) { return f == folded.front(); });
}

// Patches of folds per re-mesh (Adapter::remesh_folds_locally).
constexpr int kMostPatches = 4;

// Whether more than `most` of the folded faces lie pairwise farther apart than `apart` (their
// corner means, taken greedily in screen order): then no `most` patches, each reaching less
// than half of `apart` from its centre, can cut them all.
bool folds_farther_apart(const Mesh48& mesh, const std::vector<Face>& folded, double apart,
                         int most) {
  std::vector<Vec3> seeds;
  for (const Face f : folded) {
    const Vec3 c = face_corner_mean(mesh, f);
    if (std::none_of(seeds.begin(), seeds.end(),
                     [&](const Vec3& s) { return (s - c).norm() <= apart; }))
      seeds.push_back(c);
    if (seeds.size() > static_cast<std::size_t>(most)) return true;
  }
  return false;
}

// The saddle of F (Morse index 1 or 2: a neck's or a hole's centre) nearest to `centre` within
// `reach`, if any.
std::optional<Vec3> nearest_saddle(const std::vector<CriticalPoint>& points, const Vec3& centre,
                                   double reach) {
  std::optional<Vec3> best;
  double best_distance = reach;
  for (const CriticalPoint& c : points) {
    const double d = (c.position - centre).norm();
    if ((c.index == 1 || c.index == 2) && d <= best_distance) best = c.position, best_distance = d;
  }
  return best;
}

}  // namespace

bool Adapter::remesh_folds_locally(const MeshTopologySummary& topology, bool& changed) {
  // Faces left folded next to an event: a neck thinning towards a split narrower than its
  // edges, or tips receding from one just repaired (the wide blobs in 20 steps: 1 to 4 faces
  // within 0.05 of the saddle, twice before the split and once after it). The local repair's
  // cut, contour and stitch (local_repair.h) serve as well where the topology stays: the
  // faces around the folds are replaced by F's contour there, whose new triangles all face
  // up grad F, and the other vertices keep their identity; a global re-base otherwise.
  // A split leaves two tips, and each may fold (the torus pinched in 10 steps: one face at
  // each tip the step after, 2 apart): one patch per cluster of folds, each within half the
  // cut, until none is left.
  // A patch is centred on a saddle of F near the folds when there is one: the contour's grid
  // then has a point on it, and a neck thinner than the grid is kept (centred on the folds,
  // the contour at 0.1 missed the three blobs' necks of radius 0.03 just before their split,
  // the topology changed and the mesh was rebuilt, with 26-76 crossing pairs in the frame).
  // A patch whose faces fold again next to an earlier one (the contour's triangles across a
  // neck thinner than its spacing) is made again there at half the spacing and half the cut:
  // as many triangles, the neck resolved (the three blobs 0.0016 after their merge, neck
  // radius 0.06: folded again after each of 3 patches at 0.104, and the mesh was rebuilt).
  if (!options_.local_topology_repair) return false;
  const auto& implicit = dynamic_cast<const ImplicitSurface&>(surface_);
  const LocalRepairOptions o = local_repair_options(*topology_, probe_);
  std::vector<Face> folded, slivers;
  std::vector<Vertex> born;
  std::vector<Vec3> centres;
  std::size_t removed = 0;
  double spacing = 0.0;
  // A distance field's layer has no re-base to fall back on (rebuild_or_keep): patches made
  // before a later one failed are undone, the mesh kept as the step left it (Colin27 with
  // closing 2 in 16 steps: kept, they left 243 crossing pairs next to the cavity's hole 4 mm
  // deep; undone, 13). The copy is made only when the fold repair left folded faces.
  std::optional<Mesh48> before;
  if (topology_->fixed_points()) before.emplace(mesh_);
  changed = false;
  // Every way of giving up says why (a re-base follows, and its reason was not in the stats).
  const auto give_up = [&](const std::string& why) {
    stats_.repair_refusals.push_back("folds not re-meshed locally: " + why);
    changed = !centres.empty();  // patches made (and undone on a layer: samples redrawn)
    if (before && !centres.empty()) {
      mesh_ = std::move(*before);
      adopt_repair({});
    }
    return false;
  };
  for (int patch = 0;; ++patch) {
    find_bad_faces(mesh_, surface_, options_.fold_repair.min_angle_deg, folded, slivers);
    if (folded.empty()) break;
    if (patch == kMostPatches)
      return give_up(std::to_string(folded.size()) + " face(s) still folded after " +
                     std::to_string(kMostPatches) + " patches");
    // Folds all over the mesh (a surface no mesh can follow) need more patches than are left:
    // each attempt failed anyway. CliHostile's ripple, where a re-based mesh showed 593-1,297
    // folded faces in the next sub-step: a failed repair_locally of 11-16 s each, until the
    // re-base was refused, 3.5 minutes (refused in 5 s before with other sample draws). A patch
    // cuts within 1.5 radii of its centre (the ladder's widest cut) before its border is
    // levelled, so folds 3 radii apart need a patch each.
    if (folds_farther_apart(mesh_, folded, 3.0 * o.radius, kMostPatches - patch))
      return give_up(std::to_string(folded.size()) + " folded faces lie in more than " +
                     std::to_string(kMostPatches - patch) +
                     " places farther apart than a patch reaches");
    const std::optional<Vec3> cluster = fold_cluster_centre(mesh_, folded, 0.5 * o.radius);
    if (!cluster)
      return give_up(std::to_string(folded.size()) + " folded faces spread wider than a patch");
    const Vec3 centre =
        nearest_saddle(topology_->critical_points(), *cluster, 0.5 * o.radius).value_or(*cluster);
    LocalRepairOptions here = o;
    for (const Vec3& c : centres)
      if ((c - centre).norm() <= 0.5 * o.radius) {
        here.spacing *= 0.5;
        here.max_spacing *= 0.5;
        here.radius *= 0.5;
      }
    LocalRepairResult r = repair_locally(mesh_, implicit, centre, here);
    // On a layer, where no re-base follows, once more at half the cut and half the spacing
    // (groove14's retry): on Colin27 with closing 2 in 16 steps, without it the re-mesh at the
    // cavity's rim failed in steps 11-13 and 15 (2.75-3.75 mm deep, 6-10 s each). The narrow
    // patch's strip to a far border once left faces 1.3 mm off F and ran into the triangle budget
    // (32 steps); such a patch is now refused (local_repair.cpp).
    if (!r.repaired && before) {
      LocalRepairOptions narrower = here;
      narrower.radius *= 0.5;
      narrower.spacing *= 0.5;
      narrower.max_spacing *= 0.5;
      LocalRepairResult w = repair_locally(mesh_, implicit, centre, narrower);
      if (w.repaired) r = std::move(w);
    }
    if (!r.repaired) return give_up(r.why_not);
    adopt_repair(r.new_vertices);
    if (options_.fold_repair.enabled) repair(options_.fold_repair);
    born.insert(born.end(), r.new_vertices.begin(), r.new_vertices.end());
    centres.push_back(centre);
    removed += r.removed_faces;
    spacing = std::max(spacing, r.spacing);
  }
  if (centres.empty()) return give_up("the screen finds no folded face");
  if (const MeshTopologySummary now = summarize_topology(mesh_); !(now == topology))
    return give_up("the patches changed the topology (Euler characteristic " +
                   std::to_string(now.euler) + ", " + std::to_string(now.components) +
                   " component(s), against " + std::to_string(topology.euler) + ", " +
                   std::to_string(topology.components) + ")");
  // Nor may the new faces pass through the mesh's other sheet across the neck (the wide blobs
  // in 20 steps: 111 crossing pairs in the frame before the split, every face facing up).
  std::vector<Face> around;
  for (const Vertex v : born)  // a later patch may have cut out an earlier one's vertices
    if (mesh_.is_alive(v))
      mesh_.for_each_corner_around(v, [&](Corner c) { around.push_back(c.face); });
  if (count_face_crossings(mesh_, around) > 0) return give_up("the new faces cross the mesh");
  changed = true;
  repair_centres_.insert(repair_centres_.end(), centres.begin(), centres.end());
  stats_.folds_remeshed += stats_.folds_left;
  stats_.repair_faces_replaced += removed;
  stats_.repair_spacing = std::max(stats_.repair_spacing, spacing);
  return true;
}

bool Adapter::rebuild_if_folded() {
  const std::size_t folded = stats_.folds_left;  // what repair() could not unfold
  // A distance field's layer is re-meshed locally too, never re-based (rebuild_or_keep): where
  // that fails its folds stay reported (folds_left), as without a monitor. Colin27 with closing
  // 2 grows a groove along a ridge of the distance field on the frontal midline from 1.25 mm
  // deep, whose faces the fold repair could not unfold: every frame of a 16-step sweep to 4 mm
  // was left with 2 to 32 folded faces and 64 to 449 crossing pairs from there on (test
  // MriEvents.Colin27SweptTo4MmIsEmbeddedAtEveryFrame); re-meshed, none to 3.75 mm.
  if (folded == 0) return false;
  const auto start = std::chrono::steady_clock::now();
  const MeshTopologySummary now = summarize_topology(mesh_);  // F's (check_topology)
  bool changed = false;
  const bool remeshed = remesh_folds_locally(now, changed);
  if (remeshed || topology_->fixed_points()) {
    if (remeshed) stats_.folds_left = 0;
    stats_.topology_seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return changed;
  }
  rebuild_from_base(now.euler, now.components);
  // A re-based mesh refined into folds in more places than a re-mesh patches is where it was
  // before: the next sub-step re-meshes nothing and re-bases again, and so on. Refused, as a
  // contour that folds is (check_orientation): F has features finer than the mesh can follow.
  // CliHostile's ripple: each re-base, refined, had 822-1,675 faces folded all over the sphere,
  // and 6 re-bases, one per sub-step, came before the contour itself folded at the 7th (10.5 s
  // of CPU in all; refused at the first, 1.0 s).
  std::vector<Face>& turned = bad_faces_[0];
  std::vector<Face>& slivers = bad_faces_[1];
  find_bad_faces(mesh_, surface_, options_.fold_repair.min_angle_deg, turned, slivers,
                 &fold_screen_);
  if (folds_farther_apart(mesh_, turned, 3.0 * local_repair_options(*topology_, probe_).radius,
                          kMostPatches))
    throw std::invalid_argument(
        surface_.name() + ": at t=" + std::to_string(surface_.time()) +
        " the mesh re-based from F's contour folds over where it is refined (" +
        std::to_string(turned.size()) + " faces turned over, in more than " +
        std::to_string(kMostPatches) +
        " places): F has features finer than the contour's grid there; give --base-mesh FILE "
        "fine enough to follow them, or tighter --bounds (the grid's spacing is a 24th of their "
        "longest side)");
  topology_->mesh_rebuilt(mesh_);
  stats_.rebuilt = true;
  stats_.folds_repaired += folded;
  stats_.folds_left = 0;
  stats_.topology_seconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return true;
}

void Adapter::remesh_published_folds() {
  // Faces the repair before publishing left folded (folds_left) next to a neck thinning towards
  // its split: the three blobs in a row in 10 steps, the frame 0.0005 before the double split
  // (neck radius 0.03) had 5 such faces and 55 crossing pairs, one neck re-meshed in the last
  // sub-step, the other folded by the splits before publishing. They are re-meshed as after
  // the correction (rebuild_if_folded), the patch refined, and the frame screened again.
  // A layer whose folds could not be re-meshed is as publish_repaired left it: no measurement,
  // split pass or screen again (each step with folds left cost a measurement of every face,
  // a split pass and up to four fold repairs, with their own measurements and split passes).
  // On a layer (no re-base to fall back on) the patch's refinement and the screen after it may
  // leave faces folded again: they are re-meshed up to twice more (Colin27 with closing 2 in 8
  // steps: the frame 2.5 mm deep kept 2 folded faces and 39 crossing pairs in the frontal
  // groove after one re-mesh; now none). Elsewhere once, as before.
  for (int round = 0; round < 3; ++round) {
    if (stats_.folds_left == 0 || !options_.fold_repair.enabled) return;
    if (!rebuild_if_folded()) return;
    measure(mesh_.live_faces());
    if (options_.structural) split_pass(false);
    publish_repaired();
    if (!topology_->fixed_points()) return;
  }
}

void Adapter::forget_guarded_vertices() {
  guarded_vertices_.clear();
  guard_held_.assign(guard_held_.size(), 0);
}

void Adapter::place_guarded_vertices() {
  // The fold guard keeps a split's vertex on its edge where every place on F would turn a new
  // face over, for the next sub-step's correction to move (SurfaceProbe::project_split_vertex).
  // The splits before publishing (publish_repaired's, after its fold repair) have no next
  // sub-step: the three blobs' necks formed 0.0005 before a frame, and 27 such vertices were
  // published 0.006-0.024 off F (dense error 3.06 (T + eps)), their faces' error read low by
  // the cap at their corners. So from here on the splits are unguarded (their folds are the
  // fold repair's), and the vertices the guard kept off F during the step, whose faces were
  // held meanwhile (split_refused: such a split lowers no error), are projected, the faces
  // around them measured and refined; the fold repair before publishing mends what the
  // projection turned over.
  probe_.set_split_fold_guard(false);
  if (guarded_vertices_.empty()) return;
  std::vector<Face> around;
  for (const Vertex v : guarded_vertices_)
    if (mesh_.is_alive(v)) {
      probe_.project_vertex(mesh_, v);
      mesh_.for_each_corner_around(v, [&](Corner c) { around.push_back(c.face); });
    }
  forget_guarded_vertices();
  std::sort(around.begin(), around.end());
  around.erase(std::unique(around.begin(), around.end()), around.end());
  measure(around);
  if (options_.structural) split_pass(false);
}

void Adapter::rebuild_if_crossed() {
  // A locally repaired region is judged once more when the step ends: the sub-steps after the
  // repair move its vertices with the surface, and across a neck that keeps thinning (the wide
  // blobs in 20 steps, the frame before the split) they can pass through the other sheet while
  // every face still faces up grad F (111 crossing pairs). The faces near each repair are
  // tested against the whole mesh; a mesh that crosses itself is re-based.
  // A re-based mesh (rebuild_from_base, in this step) is all new: every face is tested. It
  // was published unchecked before (issue 16); when it crosses itself there is nothing left
  // to fall back on, so the frame is published with that said (on stderr and in the step's
  // repair_refusals), not silently.
  if (repair_centres_.empty() && !stats_.rebuilt) return;
  const auto start = std::chrono::steady_clock::now();
  if (stats_.rebuilt) {
    constexpr std::size_t kEnough = 1000;  // enough to say how badly
    if (const std::size_t pairs = count_face_crossings(mesh_, mesh_.live_faces(), kEnough);
        pairs > 0)
      stats_.repair_refusals.push_back(
          "the mesh re-based from F's contour in this step crosses itself (" +
          std::string(pairs >= kEnough ? "at least " : "") + std::to_string(pairs) +
          " face pairs that cross, each counted from both faces): this frame is not embedded");
    stats_.topology_seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return;
  }
  const double reach = 4.0 * topology_->spacing();
  std::vector<Face> near;
  for (const Face f : mesh_.live_faces()) {
    bool close = false;
    for (const Vertex v : mesh_.vertices(f))
      for (const Vec3& c : repair_centres_)
        close = close || (mesh_.position(v) - c).norm() <= reach;
    if (close) near.push_back(f);
  }
  if (count_face_crossings(mesh_, near) > 0) {
    stats_.repair_refusals.push_back(
        "the locally repaired region crossed the mesh by the end of the step");
    // A distance field's layer is not re-based for a crossing (its topology is right): its
    // base, refined 3 mm deep, ran into the triangle budget (Colin27 with closing 2 swept to 4
    // mm in 8 steps: 60,000 triangles and 21 mm of error after the frontal groove's patch
    // crossed the mesh at 3 mm), where kept the step's error stays within T + eps.
    const MeshTopologySummary now = summarize_topology(mesh_);
    if (topology_->fixed_points())
      stats_.repair_refusals.push_back("no global re-base of a layer; the crossing is kept");
    else if (rebuild_or_keep(now.euler, now.components)) {
      topology_->mesh_rebuilt(mesh_);
      stats_.rebuilt = true;
    }
  }
  stats_.topology_seconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace dynamesh
