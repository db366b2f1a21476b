#include "core/surface/volume/connected_components.h"

#include <cstdint>
#include <vector>

namespace dynamesh {
namespace {

// Breadth-first flood of the voxels with value `from` 6-connected to the seeds, setting them
// to `to` (from != to). `queue` is reused across calls. Returns the count flooded.
std::size_t flood(MaskVolume& mask, std::vector<std::uint32_t>& queue, std::uint8_t from,
                  std::uint8_t to) {
  const auto& d = mask.grid.dims;
  const std::size_t sx = 1, sy = static_cast<std::size_t>(d[0]),
                    sz = static_cast<std::size_t>(d[0]) * d[1];
  std::size_t head = 0;
  while (head < queue.size()) {
    const std::size_t v = queue[head++];
    const int i = static_cast<int>(v % sy), j = static_cast<int>((v / sy) % d[1]),
              k = static_cast<int>(v / sz);
    const auto visit = [&](bool ok, std::size_t n) {
      if (ok && mask.values[n] == from) {
        mask.values[n] = to;
        queue.push_back(static_cast<std::uint32_t>(n));
      }
    };
    visit(i > 0, v - sx);
    visit(i + 1 < d[0], v + sx);
    visit(j > 0, v - sy);
    visit(j + 1 < d[1], v + sy);
    visit(k > 0, v - sz);
    visit(k + 1 < d[2], v + sz);
  }
  const std::size_t count = queue.size();
  queue.clear();
  return count;
}

}  // namespace

std::size_t keep_largest_component(MaskVolume& mask) {
  // Flood each component to 2, remembering the seed of the largest; then flood that one
  // back to 1 and clear the rest. O(voxels), no label array.
  std::vector<std::uint32_t> queue;
  std::size_t components = 0, best = 0, best_seed = 0;
  for (std::size_t v = 0; v < mask.values.size(); ++v) {
    if (mask.values[v] != 1) continue;
    ++components;
    mask.values[v] = 2;
    queue.push_back(static_cast<std::uint32_t>(v));
    const std::size_t size = flood(mask, queue, 1, 2);
    if (size > best) {
      best = size;
      best_seed = v;
    }
  }
  if (components == 0) return 0;
  mask.values[best_seed] = 1;
  queue.push_back(static_cast<std::uint32_t>(best_seed));
  flood(mask, queue, 2, 1);
  for (auto& x : mask.values)
    if (x == 2) x = 0;
  return components;
}

std::size_t fill_holes(MaskVolume& mask) {
  // Mark the background reachable from the border as 2, then everything else is solid.
  const auto& d = mask.grid.dims;
  std::vector<std::uint32_t> queue;
  const auto seed = [&](int i, int j, int k) {
    const std::size_t v = mask.grid.index(i, j, k);
    if (mask.values[v] == 0) {
      mask.values[v] = 2;
      queue.push_back(static_cast<std::uint32_t>(v));
    }
  };
  for (int k = 0; k < d[2]; ++k)
    for (int j = 0; j < d[1]; ++j)
      for (int i = 0; i < d[0]; ++i) {
        const bool border =
            i == 0 || j == 0 || k == 0 || i == d[0] - 1 || j == d[1] - 1 || k == d[2] - 1;
        if (border) seed(i, j, k);
      }
  flood(mask, queue, 0, 2);
  std::size_t filled = 0;
  for (auto& x : mask.values) {
    if (x == 0) ++filled;
    x = (x == 2) ? 0 : 1;
  }
  return filled;
}

}  // namespace dynamesh
