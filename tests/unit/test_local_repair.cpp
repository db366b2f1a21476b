// The local repair of a topology change (core/topology/local_repair.h) carried out on the mesh
// exactly as planned on its trial copy: the repair's splits put their vertices by the mesh's own
// rule (the adapter's: SurfaceProbe::project_split_vertex, the fold guard on as after an event),
// so the mesh ends with the positions the successful attempt planned, bit for bit.
#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <string>

#include "core/adapt/adapter.h"
#include "core/adapt/surface_probe.h"
#include "core/surface/scene_registry.h"
#include "core/topology/local_repair.h"
#include "core/topology/topology_events.h"

namespace dynamesh {
namespace {

using Rule = std::function<void(Mesh48&, const DiamondChange&)>;

// The adapter's rule after an event (its tracker: SurfaceProbe::project_split_vertex with the
// fold guard on).
Rule adapter_rule(const SurfaceProbe& probe) {
  return [&probe](Mesh48& mesh, const DiamondChange& change) {
    probe.place_split_vertex(mesh, change);
    probe.project_split_vertex(mesh, change);
  };
}
// What that rule does where the fold guard finds that every place would turn a new face over:
// the vertex stays at its parents' midpoint (where Mesh48::split put it).
void midpoint_rule(Mesh48&, const DiamondChange&) {}

// A mesh's listener that places split vertices by `rule`, and counts those it put elsewhere than
// the repair's own rule (split_point_on_surface) would.
class Placement : public MeshListener {
 public:
  Placement(const ImplicitSurface& surface, Rule rule)
      : surface_(surface), rule_(std::move(rule)) {}
  void after_split(Mesh48& mesh, const DiamondChange& change) override {
    rule_(mesh, change);
    ++born;
    const Vec3 local = split_point_on_surface(surface_, mesh.position(change.parents[0]),
                                              mesh.position(change.parents[1]));
    differing += local != mesh.position(change.vertex);
  }
  void after_weld(Mesh48&, const DiamondChange&) override {}
  void after_renumber(Mesh48&, const Renumbering&) override {}
  int born = 0, differing = 0;

 private:
  const ImplicitSurface& surface_;
  Rule rule_;
};

struct EventCase {
  std::string scene;
  std::unique_ptr<Surface> surface;
  int steps, event_step;
  Vec3 centre;  // of the event
  AdaptOptions options;
};

// The torus pinch (assets/examples/torus-pinch.args) adapted until the step that pinches it
// (step 20 of 40, t = 0.5) begins, and that step's event repaired as the adapter repairs it
// (local_repair_options in adapter_topology.cpp) on a copy of the mesh whose listener places
// split vertices by `listener_rule`; the repair is told `repair_rule`.
struct Repaired {
  LocalRepairResult result;
  Mesh48 before, mesh;
  int born = 0, differing = 0;
};
Repaired repair_torus_pinch(const std::function<Rule(const SurfaceProbe&)>& listener_rule,
                            const std::function<Rule(const SurfaceProbe&)>& repair_rule) {
  constexpr int kSteps = 40, kEventStep = 20;
  const auto made = make_scene(
      "expr", {},
      {{"implicit", "(sqrt(x^2+y^2)-1)^2 + z^2 - 0.09 + 0.18*t*exp(-((x-1)^2+y^2+z^2)/0.16)"},
       {"bounds", "-1.5,-1.5,-0.5,1.5,1.5,0.5"}});
  auto& surface = dynamic_cast<ImplicitSurface&>(*made);
  const AdaptOptions o;
  Adapter adapter(surface, o, default_criteria("expr", 0.0, o, 0.0));
  adapter.initialize();
  for (int s = 1; s < kEventStep; ++s) adapter.step(static_cast<double>(s) / kSteps);
  Repaired out;
  out.before = adapter.mesh();
  out.before.clear_listeners();
  out.mesh = out.before;
  surface.set_time(static_cast<double>(kEventStep) / kSteps);
  TopologyMonitor monitor(ContourBaseOptions{}, o.threshold);
  monitor.reset(surface, out.mesh);
  const double cell = monitor.spacing();
  SurfaceProbe probe(surface);
  probe.set_split_fold_guard(true);
  Placement placement(surface, listener_rule(probe));
  out.mesh.add_listener(&placement);
  LocalRepairOptions r;
  r.radius = 2.0 * cell;
  r.spacing = 0.5 * cell;
  r.max_spacing = 0.75 * cell;
  r.place_split_vertex = repair_rule(probe);
  out.result = repair_locally(out.mesh, surface, Vec3(1, 0, 0), r);
  out.mesh.clear_listeners();
  out.born = placement.born;
  out.differing = placement.differing;
  return out;
}

// Live vertices whose position differs, bit for bit, from the one the repair planned.
std::size_t off_plan(const Repaired& r) {
  std::size_t off = 0;
  for (const Vertex v : r.mesh.live_vertices())
    off += r.mesh.position(v) != r.result.planned_positions.at(v.idx);
  return off;
}

// The repair's splits (7 here, levelling the cut's border) placed by a rule other than the
// repair's own projection (the fold guard leaving every vertex at its midpoint): the trial copy
// plans on that rule's positions, and the mesh ends with exactly those. (On main's code the copy
// projected the vertices onto F and the mesh kept them at the midpoints: 7 vertices off the
// plan, the seam's triangles stitched to positions the mesh did not have.)
TEST(LocalRepair, MeshEndsWithThePlannedPositionsUnderTheCallersRule) {
  const auto midpoint = [](const SurfaceProbe&) { return Rule(midpoint_rule); };
  const Repaired r = repair_torus_pinch(midpoint, midpoint);
  ASSERT_TRUE(r.result.repaired) << r.result.why_not;
  EXPECT_GT(r.born, 0);
  EXPECT_EQ(r.differing, r.born);  // the two rules differ at every split
  EXPECT_EQ(off_plan(r), 0u);
  EXPECT_EQ(summarize_topology(r.mesh), (MeshTopologySummary{2, 1}));  // pinched: a bent tube
}

// The adapter's own rule (SurfaceProbe, fold guard on): the same, bit for bit.
TEST(LocalRepair, MeshEndsWithThePlannedPositionsUnderTheAdaptersRule) {
  const Repaired r = repair_torus_pinch(adapter_rule, adapter_rule);
  ASSERT_TRUE(r.result.repaired) << r.result.why_not;
  EXPECT_GT(r.born, 0);
  EXPECT_EQ(off_plan(r), 0u);
  EXPECT_EQ(summarize_topology(r.mesh), (MeshTopologySummary{2, 1}));
}

// A repair told a rule that is not the mesh's listeners' finds the replayed vertices off the
// plan and refuses the surgery: the mesh keeps its topology (the splits made stay).
TEST(LocalRepair, RuleThatIsNotTheListenersIsRefusedBeforeTheSurgery) {
  const Repaired r =
      repair_torus_pinch([](const SurfaceProbe&) { return Rule(midpoint_rule); }, adapter_rule);
  EXPECT_FALSE(r.result.repaired);
  EXPECT_NE(r.result.why_not.find("elsewhere than on the copy"), std::string::npos)
      << r.result.why_not;
  EXPECT_GT(r.born, 0);
  EXPECT_EQ(summarize_topology(r.mesh), summarize_topology(r.before));
  EXPECT_EQ(r.mesh.n_faces(), r.before.n_faces() + 2 * static_cast<std::size_t>(r.born));
}

}  // namespace
}  // namespace dynamesh
