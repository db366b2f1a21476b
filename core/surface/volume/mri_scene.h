// The `mri` entry of the scene catalogue: text option "volume" (a NIfTI file, by default
// Colin27 from mricron-data), parameters depth_max and threshold, and adaptation settings
// in millimetres. Listing it loads nothing.
#pragma once

#include "core/surface/scene_registry.h"

namespace dynamesh {

// Suggested adaptation settings for brain layers: T = 0.5 mm, a fifth of the cortex's
// thickness and half a voxel of Colin27; 2 samples per mm^2. Measured on Colin27 over depths
// 0-15 mm (4,100-7,400 triangles): 22-27 samples per triangle, as for the analytic scenes at
// their defaults, and a dense error at most 1.05 (T + eps); 1 per mm^2 reached 1.10.
inline constexpr SceneSuggestions kMriSuggestions{0.5, 2.0};  // mm, samples per mm^2

SceneRegistration mri_scene_registration();

}  // namespace dynamesh
