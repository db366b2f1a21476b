#include "core/surface/volume/brain_extraction.h"

#include <cstdint>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "core/io/number_text.h"
#include "core/surface/volume/distance_transform.h"

namespace dynamesh {
namespace {

struct Piece {
  std::size_t voxels = 0;
  bool touches_border = false;
};

// 6-connected pieces of `mask`: a label per voxel (0 = background, piece p has label p + 1).
std::vector<Piece> label_pieces(const MaskVolume& mask, std::vector<std::uint32_t>& label) {
  const auto& d = mask.grid.dims;
  const std::size_t sy = static_cast<std::size_t>(d[0]), sz = sy * d[1];
  label.assign(mask.values.size(), 0);
  std::vector<Piece> pieces;
  std::vector<std::size_t> queue;
  for (std::size_t seed = 0; seed < mask.values.size(); ++seed) {
    if (!mask.values[seed] || label[seed]) continue;
    pieces.emplace_back();
    const auto id = static_cast<std::uint32_t>(pieces.size());
    Piece& piece = pieces.back();
    label[seed] = id;
    queue.assign(1, seed);
    for (std::size_t head = 0; head < queue.size(); ++head) {
      const std::size_t v = queue[head];
      const int i = static_cast<int>(v % sy), j = static_cast<int>((v / sy) % d[1]),
                k = static_cast<int>(v / sz);
      piece.touches_border = piece.touches_border || i == 0 || j == 0 || k == 0 || i + 1 == d[0] ||
                             j + 1 == d[1] || k + 1 == d[2];
      const auto visit = [&](bool ok, std::size_t n) {
        if (ok && mask.values[n] && !label[n]) {
          label[n] = id;
          queue.push_back(n);
        }
      };
      visit(i > 0, v - 1);
      visit(i + 1 < d[0], v + 1);
      visit(j > 0, v - sy);
      visit(j + 1 < d[1], v + sy);
      visit(k > 0, v - sz);
      visit(k + 1 < d[2], v + sz);
    }
    piece.voxels = queue.size();
  }
  return pieces;
}

}  // namespace

MaskVolume extract_brain(const MaskVolume& head, const BrainExtractionOptions& options,
                         std::vector<float>& squared) {
  const float r2 = static_cast<float>(options.erosion_mm * options.erosion_mm);
  const double ml_per_voxel = head.grid.voxel_volume() / 1000.0;
  // Erosion: what lies farther than the radius from any dark voxel.
  MaskVolume core(head.grid, 0);
  squared_distance_transform(head, 0, squared);
  for (std::size_t v = 0; v < core.values.size(); ++v)
    core.values[v] = head.values[v] && squared[v] > r2 ? 1 : 0;
  // The brain prior picks the largest eroded piece away from the border.
  std::vector<std::uint32_t> label;
  const std::vector<Piece> pieces = label_pieces(core, label);
  std::uint32_t best = 0;
  std::size_t best_voxels = 0;
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    if (pieces[p].touches_border || pieces[p].voxels <= best_voxels) continue;
    best = static_cast<std::uint32_t>(p + 1);
    best_voxels = pieces[p].voxels;
  }
  for (std::size_t v = 0; v < core.values.size(); ++v) core.values[v] = label[v] == best ? 1 : 0;
  // Dilation by the same radius, inside the head: the brain's own outline back.
  MaskVolume brain(head.grid, 0);
  std::size_t voxels = 0;
  if (best != 0) {
    squared_distance_transform(core, 1, squared);
    for (std::size_t v = 0; v < brain.values.size(); ++v) {
      brain.values[v] = head.values[v] && squared[v] <= r2 ? 1 : 0;
      voxels += brain.values[v];
    }
  }
  const double ml = static_cast<double>(voxels) * ml_per_voxel;
  if (best == 0 || ml < options.min_volume_ml || ml > options.max_volume_ml) {
    throw std::invalid_argument(
        "brain extraction: no brain-like piece in this head (" +
        (best == 0
             ? std::string("every piece left by a ") + format_significant(options.erosion_mm, 3) +
                   " mm erosion touches the volume's border"
             : "the largest piece holds " + format_significant(ml, 3) + " ml, outside " +
                   format_significant(options.min_volume_ml, 3) + "-" +
                   format_significant(options.max_volume_ml, 3) + " ml") +
        "); pass a brain mask with --mask FILE (e.g. from FSL BET or SynthStrip)");
  }
  return brain;
}

MaskVolume extract_brain(const MaskVolume& head, const BrainExtractionOptions& options) {
  std::vector<float> squared;
  return extract_brain(head, options, squared);
}

}  // namespace dynamesh
