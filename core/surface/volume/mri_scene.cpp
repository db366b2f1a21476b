#include "core/surface/volume/mri_scene.h"

#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "core/io/label_atlas.h"
#include "core/surface/parameter_table.h"
#include "core/surface/volume/mri_surface.h"

namespace dynamesh {
namespace {

constexpr const char* kVolumeOption = "volume";
constexpr const char* kMaskOption = "mask";
constexpr const char* kAtlasOption = "atlas";

// Colin27 (ch2*.nii.gz in mricron-data) is registered with the AAL atlas shipped beside it
// (aal.nii.gz, same 1 mm MNI grid): that atlas is the default for it; other scans have none.
std::filesystem::path default_atlas(const std::filesystem::path& volume) {
  const std::string name = volume.filename().string();
  const std::filesystem::path aal = volume.parent_path() / "aal.nii.gz";
  std::error_code ec;
  if (name.rfind("ch2", 0) == 0 && std::filesystem::is_regular_file(aal, ec)) return aal;
  return {};
}

// Reads --atlas and checks that it lies where the scan is (an atlas of another space would
// label nothing, silently).
std::shared_ptr<const LabelAtlas> load_atlas(const std::filesystem::path& path,
                                             const MriSurface& surface) {
  std::shared_ptr<LabelAtlas> atlas;
  try {
    atlas = std::make_shared<LabelAtlas>(read_label_atlas(path));
  } catch (const std::runtime_error& e) {
    throw std::invalid_argument(std::string("mri: --atlas: ") + e.what());
  }
  const Box3 a = atlas->labels.grid.world_bounds(), b = surface.layers().mask_bounds();
  if (!a.overlaps(b))
    throw std::invalid_argument("mri: --atlas " + path.string() +
                                " does not overlap the brain (a label volume in another space?)");
  return atlas;
}

SurfaceParameter closing_parameter() {
  return {"closing", MriOptions{}.closing_radius_mm, kMinClosingMm, kMaxClosingMm, kClosingHelp};
}

// The numbers the builder itself uses: building with the segmentation threshold avoids
// segmenting and transforming twice. Out-of-range values are left to make_scene, whose
// range check gives the usual message.
void take_overrides(const ParameterOverrides& overrides, MriOptions& options) {
  for (const auto& [key, value] : overrides) {
    // The closing's range does not depend on the volume: refused before loading it.
    if (key == "closing") check_parameter_value(MriSurface::kName, closing_parameter(), value);
    if (!std::isfinite(value) || value < 0.0) continue;
    if (key == "threshold") options.threshold = value;
    if (key == "depth_max") options.depth_max = value;
    if (key == "closing") {
      options.closing_radius_mm = value;
      options.closing_given = true;
    }
  }
}

std::unique_ptr<Surface> build_mri_scene(const SceneRequest& request) {
  MriOptions options;
  bool volume_given = false;
  std::filesystem::path atlas_path;
  for (const auto& [key, value] : request.text_options) {
    if (key == kMaskOption) {
      options.mask_path = value;
      continue;
    }
    if (key == kAtlasOption) {
      atlas_path = value;
      continue;
    }
    if (key != kVolumeOption) {
      throw std::invalid_argument("mri: unknown option '" + key +
                                  "' (its options are --volume FILE.nii[.gz], --mask "
                                  "FILE.nii[.gz] and --atlas FILE.nii[.gz])");
    }
    options.volume_path = value;
    volume_given = true;
  }
  take_overrides(request.overrides, options);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(options.volume_path, ec) &&
      !std::filesystem::is_directory(options.volume_path, ec)) {
    if (!volume_given) {
      throw std::invalid_argument(
          std::string("mri: the default volume ") + kDefaultMriVolume +
          " is not installed; install the Debian package mricron-data or pass --volume "
          "FILE.nii[.gz]");
    }
    throw std::invalid_argument("mri: volume '" + options.volume_path.string() +
                                "' is not a readable file (--volume takes a NIfTI .nii or "
                                ".nii.gz file, or a folder holding one DICOM series)");
  }
  options.progress = request.progress;
  options.max_memory_mb = request.max_memory_mb;
  std::unique_ptr<MriSurface> surface;
  try {
    surface = make_mri_surface(options);
  } catch (const std::runtime_error& e) {
    // An unreadable or malformed file is bad input like a missing one.
    throw std::invalid_argument(std::string("mri: ") + e.what());
  }
  if (atlas_path.empty()) atlas_path = default_atlas(options.volume_path);
  if (!atlas_path.empty()) surface->set_atlas(load_atlas(atlas_path, *surface));
  surface->set_progress({});
  return surface;
}

}  // namespace

SceneRegistration mri_scene_registration() {
  // Nominal ranges: the exact ones (depth_max below the deepest point, threshold up to the
  // brightest voxel) are known once a volume is loaded and are checked then.
  std::vector<SurfaceParameter> listed{
      {"depth_max", MriOptions{}.depth_max, 0.0, 80.0,
       "depth in mm of the layer at t = 1 below the brain's surface (at most the brain's "
       "depth - 1 mm)"},
      {"threshold", 0.0, 0.0, 32767.0,
       "segmentation intensity threshold, at most the volume's maximum; 0 means Otsu's"},
      closing_parameter()};
  SceneRegistration r;
  r.name = MriSurface::kName;
  r.description = std::string(MriSurface::kDescription) +
                  "; input --volume FILE.nii[.gz], by default Colin27 (mricron-data)";
  r.build = build_mri_scene;
  r.listed_parameters = std::move(listed);
  r.suggestions = kMriSuggestions;
  return r;
}

}  // namespace dynamesh
