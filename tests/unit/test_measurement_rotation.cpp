// The measurement rotation (core/adapt/measurement_rotation.h): every face is on turn at least
// once in every kRotation steps, also across renumberings and the regrouping of the turns into
// blocks of neighbours; the blocks keep the turns balanced; and on an adapted mesh the faces of
// one turn are patches, whose shared edges are read once.
//
// The independent check: each face's last turn is kept by the test itself, from on_turn() at
// every step, and follows the renumberings through the test's own permutations.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <numeric>
#include <random>

#include "core/adapt/measurement_rotation.h"
#include "scene_run.h"

namespace dynamesh {
namespace {

constexpr std::uint32_t kRotation = MeasurementRotation::kRotation;

// A random permutation of `n` slots that drops `dropped` of them (they die).
Renumbering shuffle_faces(std::size_t n, std::size_t dropped, std::mt19937& rng) {
  Renumbering r;
  r.n_faces = n - dropped;
  std::vector<std::uint32_t> ids(n);
  std::iota(ids.begin(), ids.end(), 0u);
  std::shuffle(ids.begin(), ids.end(), rng);
  r.face.assign(n, kInvalidIndex);
  for (std::size_t k = 0; k < r.n_faces; ++k) r.face[ids[k]] = static_cast<std::uint32_t>(k);
  return r;
}

TEST(MeasurementRotation, NoFaceWaitsLongerThanTheRotation) {
  std::mt19937 rng(5);
  MeasurementRotation rotation;
  std::size_t n = 20000;
  rotation.grow(n);
  rotation.set_every_turn();
  std::vector<std::uint64_t> last(n, 0);  // step 0 measured every face
  std::size_t regrouped_pending = 0;
  std::uint64_t longest = 0;
  for (std::uint64_t step = 1; step <= 400; ++step) {
    rotation.set_step(step);
    for (std::size_t f = 0; f < n; ++f) {
      longest = std::max(longest, step - last[f]);  // (at most kRotation - 1 if not on turn)
      if (rotation.on_turn(Face(static_cast<std::uint32_t>(f)))) last[f] = step;
    }
    ASSERT_LE(longest, kRotation) << "step " << step;
    // Between steps, at every phase of the rotation and sometimes on consecutive steps: a
    // renumbering (some faces die, new ones are born and measured now), then the turns
    // regrouped in the new order.
    if (step % 7 == 0 || step % 11 == 0) {
      const Renumbering r = shuffle_faces(n, n / 10, rng);
      rotation.renumber(r);
      std::vector<std::uint64_t> moved(r.n_faces);
      for (std::size_t f = 0; f < n; ++f)
        if (r.face[f] != kInvalidIndex) moved[r.face[f]] = last[f];
      last = std::move(moved);
      n = r.n_faces + n / 10;
      rotation.grow(n);
      last.resize(n, step);  // born (split) faces are measured when they are made
      rotation.group_in_order();
      regrouped_pending = std::max(regrouped_pending, rotation.pending());
    }
  }
  EXPECT_EQ(longest, kRotation);  // the rotation's own period
  // Regrouping right away would have made these wait longer: the pending path was taken.
  EXPECT_GT(regrouped_pending, n / 4);
}

TEST(MeasurementRotation, RegroupedTurnsAreBlocksInIdOrder) {
  MeasurementRotation rotation;
  const std::size_t n = 100000;
  rotation.grow(n);
  rotation.set_step(3);
  rotation.group_in_order();
  EXPECT_GT(rotation.pending(), 0u);
  for (std::uint64_t step = 4; step < 4 + kRotation; ++step) rotation.set_step(step);
  EXPECT_EQ(rotation.pending(), 0u);  // each pending face's old turn came within the rotation
  const std::size_t block = MeasurementRotation::turn_block(n);
  EXPECT_EQ(block, n / (kRotation * MeasurementRotation::kBlocksPerTurn));
  for (std::size_t f = 0; f < n; ++f)
    ASSERT_EQ(rotation.turn(Face(static_cast<std::uint32_t>(f))), f / block % kRotation) << f;
}

TEST(MeasurementRotation, TurnsStayBalanced) {
  for (const std::size_t n : {40ul, 5000ul, 123457ul, 2000000ul}) {
    MeasurementRotation rotation;
    rotation.grow(n);
    rotation.set_every_turn();
    rotation.group_in_order();  // every face was just measured: all regrouped now
    EXPECT_EQ(rotation.pending(), 0u);
    std::array<std::size_t, kRotation> count{};
    for (std::size_t f = 0; f < n; ++f) ++count[rotation.turn(Face(static_cast<std::uint32_t>(f)))];
    const std::size_t block = MeasurementRotation::turn_block(n);
    EXPECT_LE(block, MeasurementRotation::kMaxBlock);
    const auto [fewest, most] = std::minmax_element(count.begin(), count.end());
    EXPECT_LE(*most - *fewest, block) << n;
    EXPECT_LE(static_cast<double>(*most - *fewest), 0.07 * static_cast<double>(n) / kRotation + 1)
        << n;
  }
}

// On an adapted, renumbered mesh most edges join two faces of the same turn (about 1 in 16 with
// the turns id % 16 of unrenumbered slots), and measuring shares their peaks.
TEST(MeasurementRotation, AdaptedMeshMeasuresPatchesOfNeighbours) {
  AdaptOptions o;
  o.threshold = 5e-4;  // ~10,000 vertices: more than one locality window (kLocalityWindow)
  o.epsilon = 1.25e-4;
  AdaptOptions unrenumbered = o;
  unrenumbered.renumber = false;
  auto grouped = test::start_scene("capsule-bend", o, 0.5);
  auto scattered = test::start_scene("capsule-bend", unrenumbered, 0.5);
  ASSERT_TRUE(grouped.adapter->stats().renumbered);
  const auto same_turn_share = [](const Adapter& a) {
    const Mesh48& mesh = a.mesh();
    std::size_t same = 0, edges = 0;
    for (const Face f : mesh.live_faces())
      for (int e = 0; e < 3; ++e) {
        const Face g = mesh.neighbor(f, e);
        if (!g.is_valid() || g.idx < f.idx) continue;
        ++edges;
        same += a.samples().rotation().turn(f) == a.samples().rotation().turn(g);
      }
    return static_cast<double>(same) / static_cast<double>(edges);
  };
  EXPECT_GT(same_turn_share(*grouped.adapter), 0.8);
  EXPECT_LT(same_turn_share(*scattered.adapter), 0.2);
  const std::uint64_t shared_before[2] = {grouped.adapter->samples().edge_peaks_shared(),
                                          scattered.adapter->samples().edge_peaks_shared()};
  double t = 0.5;
  for (int k = 0; k < 4; ++k) {
    t += 2e-3;
    grouped.adapter->step(t);
    scattered.adapter->step(t);
  }
  const std::uint64_t shared[2] = {
      grouped.adapter->samples().edge_peaks_shared() - shared_before[0],
      scattered.adapter->samples().edge_peaks_shared() - shared_before[1]};
  // Also the scattered run shares edges between the faces a split or weld made, measured
  // together: the patches more than double the sharing.
  EXPECT_GT(shared[0], 2 * shared[1]) << shared[0] << " against " << shared[1];
}

}  // namespace
}  // namespace dynamesh
