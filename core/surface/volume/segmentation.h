// Segmentation of a brain-extracted MR volume into one solid brain mask (SCENES.md, mri,
// step 1): light Gaussian smoothing, a threshold (Otsu's by default), the largest
// face-connected component, an optional morphological closing (the brain's envelope, which
// bridges sulci so that layers below it are smooth "peels" as in curvilinear reformatting),
// and the holes filled.
#pragma once

#include <cstddef>
#include <vector>

#include "core/surface/volume/brain_extraction.h"
#include "core/surface/volume/progress.h"
#include "core/surface/volume/voxel_grid.h"

namespace dynamesh {

struct SegmentationOptions {
  double smoothing_sigma_mm = 1.0;  // Gaussian before thresholding; <= 0: none
  double threshold = 0.0;           // intensity; <= 0 means Otsu's threshold
  // Ball radius of an opening before the largest component is kept: it cuts threads thinner
  // than twice the radius (vessels, nerves, dura left by skull stripping) whose layers are
  // strings of sub-voxel bubbles that no coarse mesh can follow. <= 0: none.
  double opening_radius_mm = 0.0;
  double closing_radius_mm = 0.0;  // ball radius of the closing; <= 0: none
  // > 0: the closing is sized to the anatomy: a component larger than this (ml) gets a
  // radius closing_radius_mm * cbrt(volume / closing_reference_ml), so that a brain n times
  // larger in every direction (its sulci n times wider) is closed like the reference one.
  // Never smaller than closing_radius_mm. 0: the radius as given.
  double closing_reference_ml = 0.0;
  // Plausibility of the largest component, checked before the closing so that a scan that is
  // not a brain fails within seconds (a head with its skull touches the volume's border
  // where the neck leaves it: ~100 cm^2 on Colin27's ch2; a random volume percolates to the
  // border). 0: no check.
  double max_border_contact_mm2 = 0.0;
  double min_volume_ml = 0.0, max_volume_ml = 0.0;
  // A thresholded volume whose largest component touches the border beyond
  // max_border_contact_mm2 is taken for a head with its skull and the brain is extracted
  // from it (brain_extraction.h) before the checks; false: it is refused.
  bool extract_brain = false;
  BrainExtractionOptions extraction;
};

struct Segmentation {
  MaskVolume mask;
  double threshold = 0.0;          // the threshold used
  bool otsu = false;               // whether it was Otsu's
  std::size_t components = 0;      // face-connected components above the threshold
  std::size_t holes_filled = 0;    // voxels
  std::size_t voxels = 0;          // in the final mask
  bool extracted = false;          // whether the brain was extracted from a head
  double closing_radius_mm = 0.0;  // the closing's radius (after sizing to the anatomy)
  double volume_ml() const { return voxels * mask.grid.voxel_volume() / 1000.0; }
};

// Throws std::invalid_argument when nothing lies above the threshold, or when the largest
// component fails the plausibility limits (the message names --mask).
Segmentation segment_volume(const ScalarVolume& intensity, const SegmentationOptions& options,
                            const ProgressCallback& progress = {});
// The same from a mask made elsewhere (nonzero = inside): opening, largest component, checks,
// closing and holes, as after thresholding; options.threshold and smoothing are unused.
Segmentation segment_mask(MaskVolume mask, const SegmentationOptions& options,
                          const ProgressCallback& progress = {});

// Morphological closing of `mask` by a ball of `radius_mm` (dilation then erosion, both by
// thresholding exact Euclidean distance transforms). Voxels outside the grid count as
// background for the erosion only as far as the grid reaches.
void close_mask(MaskVolume& mask, double radius_mm);
// Morphological opening (erosion then dilation by a ball of `radius_mm`).
void open_mask(MaskVolume& mask, double radius_mm);
// The same with a caller's buffer for the squared distances (reused across calls).
void close_mask(MaskVolume& mask, double radius_mm, std::vector<float>& scratch);
void open_mask(MaskVolume& mask, double radius_mm, std::vector<float>& scratch);

}  // namespace dynamesh
