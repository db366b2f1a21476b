// One topology event of a deforming implicit surface (issue 16): when, where and what.
// Found by TopologyMonitor (topology_events.h); carried in StepStats.
#pragma once

#include "core/geometry/vector_types.h"

namespace dynamesh {

enum class TopologyEventKind { kBirth, kDeath, kMerge, kSplit, kHoleCloses, kHoleOpens, kMismatch };

// "birth", "death", "merge", "split", "hole-closes", "hole-opens", "mismatch".
const char* to_string(TopologyEventKind kind);

struct TopologyEvent {
  double time = 0.0;
  Vec3 position{Vec3::Zero()};
  TopologyEventKind kind = TopologyEventKind::kMismatch;
};

}  // namespace dynamesh
