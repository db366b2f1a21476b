// Reading an anatomical label atlas: a NIfTI label volume (integer region per voxel, placed in
// the world by its own sform/qform like any scan) and its names from the mricron sidecar
// FILE.nii.txt beside FILE.nii[.gz], one "index name [more...]" line per region (AAL, AICHA,
// JHU in mricron-data). `--atlas FILE.nii.gz`, issue 14.
#pragma once

#include <filesystem>
#include <map>
#include <string>

#include "core/surface/volume/volume_image.h"

namespace dynamesh {

// The sidecar of an atlas file: aal.nii.gz -> aal.nii.txt, aal.nii -> aal.nii.txt.
std::filesystem::path atlas_names_path(const std::filesystem::path& atlas);
// "index name ..." lines; blank lines and lines without a leading integer are skipped.
std::map<int, std::string> parse_atlas_names(const std::string& text);
// Throws std::runtime_error naming the file when the volume cannot be read or holds
// non-integer labels; a missing sidecar leaves the names empty ("region N").
LabelAtlas read_label_atlas(const std::filesystem::path& path);

}  // namespace dynamesh
