// Per-step statistics of the last few hundred steps, for the panel's plots (not saved: it is
// a record, not a setting).
#pragma once

#include <cstddef>
#include <vector>

#include "core/adapt/step_stats.h"

namespace dynamesh {

class StatsHistory {
 public:
  static constexpr std::size_t kCapacity = 500;  // steps kept; older ones scroll out

  struct Series {
    std::vector<float> triangles, max_error, mean_error, splits, welds, step_ms, kept_percent;
  };

  void add(const StepStats& s) {
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
    push(series_.kept_percent, s.vertices == 0 ? 0.0 : 100.0 * static_cast<double>(s.vertices_kept) /
                                                           static_cast<double>(s.vertices));
  }
  void clear() { series_ = Series{}; }
  const Series& series() const { return series_; }
  std::size_t size() const { return series_.triangles.size(); }

 private:
  Series series_;
};

}  // namespace dynamesh
