// Per-step statistics of the last few hundred steps, for the panel's plots (not saved: it is
// a record, not a setting).
#pragma once

#include <cstddef>
#include <cstdio>
#include <string>
#include <vector>

#include "core/adapt/step_stats.h"
#include "core/topology/topology_event.h"

namespace dynamesh {

class StatsHistory {
 public:
  static constexpr std::size_t kCapacity = 500;  // steps kept; older ones scroll out

  struct Series {
    std::vector<float> triangles, max_error, mean_error, splits, welds, step_ms, kept_percent;
  };

  // What a step did about the surface's topology (issue 16), one line per event, with how the
  // mesh followed: "step 7 t=0.1515: merge near (0.00, 0.00, 0.00), repaired locally (317
  // faces)". Empty when nothing happened.
  static std::vector<std::string> topology_notes(const StepStats& s) {
    std::vector<std::string> notes;
    char how[96];
    if (s.rebuilt)
      std::snprintf(how, sizeof how, "mesh rebuilt from F's contour");
    else if (s.local_repairs > 0)
      std::snprintf(how, sizeof how, "repaired locally (%zu faces)", s.repair_faces_replaced);
    else
      std::snprintf(how, sizeof how, "mesh unchanged");
    for (const TopologyEvent& e : s.topology_events) {
      char line[200];
      std::snprintf(line, sizeof line, "step %zu t=%.4f: %s near (%.2f, %.2f, %.2f), %s",
                    static_cast<std::size_t>(s.step), e.time, to_string(e.kind), e.position.x(),
                    e.position.y(), e.position.z(), how);
      notes.emplace_back(line);
    }
    return notes;
  }

  void add(const StepStats& s) {
    for (std::string& note : topology_notes(s)) {
      if (events_.size() == kEventsKept) events_.erase(events_.begin());
      events_.push_back(std::move(note));
    }
    const auto push = [](std::vector<float>& v, double x) {
      if (v.size() == kCapacity) v.erase(v.begin());
      v.push_back(static_cast<float>(x));
    };
    push(series_.triangles, static_cast<double>(s.triangles));
    push(series_.max_error, s.max_error);
    push(series_.mean_error, s.mean_error);
    push(series_.splits, static_cast<double>(s.splits));
    push(series_.welds, static_cast<double>(s.welds));
    push(series_.step_ms, 1e3 * s.seconds.total);
    push(series_.kept_percent, s.vertices == 0 ? 0.0
                                               : 100.0 * static_cast<double>(s.vertices_kept) /
                                                     static_cast<double>(s.vertices));
  }
  void clear() {
    series_ = Series{};
    events_.clear();
  }
  const Series& series() const { return series_; }
  // The last few topology notes of the run, oldest first.
  const std::vector<std::string>& topology_events() const { return events_; }
  std::size_t size() const { return series_.triangles.size(); }

 private:
  static constexpr std::size_t kEventsKept = 8;
  Series series_;
  std::vector<std::string> events_;
};

}  // namespace dynamesh
