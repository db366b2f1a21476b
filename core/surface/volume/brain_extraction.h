// Built-in brain extraction for a T1-weighted head scan with its skull (SCENES.md, mri;
// issue 14): morphology, connected components and a brain prior, the classic recipe of
// morphological skull stripping (M. E. Brummer, R. M. Mersereau, R. L. Eisner, R. R. J.
// Lewine, "Automatic detection of brain contours in MRI data sets", IEEE Trans. Medical
// Imaging 12(2), 1993; D. W. Shattuck et al., "Magnetic resonance image tissue
// classification using a partial volume model", NeuroImage 13(5), 2001, its Brain Surface
// Extractor). In a T1 scan the brain is bright and wrapped in dark cerebrospinal fluid and
// skull; the bright scalp, marrow and neck touch it only through thin bridges (optic
// nerves, vessels, partial-volume voxels). An erosion cuts those bridges, the brain is the
// largest eroded piece that stays away from the volume's border (the neck leaves the volume
// there), and a dilation by the same radius inside the head's mask gives its shape back.
#pragma once

#include <vector>

#include "core/surface/volume/voxel_grid.h"

namespace dynamesh {

struct BrainExtractionOptions {
  // Erosion radius: wider than the bridges between brain and scalp (measured on Colin27's
  // ch2), thinner than half the brain's thickness.
  double erosion_mm = 8.0;
  // The brain prior: the extracted piece must hold a human-brain-like volume (a newborn's
  // brain is ~0.35 L, an adult's 1-1.8 L; generous on both sides) and stay off the border.
  double min_volume_ml = 300.0, max_volume_ml = 3000.0;
};

// `head`: the thresholded head (1 = bright tissue). Returns the brain's mask on the same
// grid. Throws std::invalid_argument when no piece fits the prior (one line, naming --mask).
MaskVolume extract_brain(const MaskVolume& head, const BrainExtractionOptions& options = {});
// The same with a caller's buffer for the squared distances (reused across transforms).
MaskVolume extract_brain(const MaskVolume& head, const BrainExtractionOptions& options,
                         std::vector<float>& squared);

}  // namespace dynamesh
