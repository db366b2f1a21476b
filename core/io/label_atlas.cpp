#include "core/io/label_atlas.h"

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "core/io/nifti_volume.h"

namespace dynamesh {

std::filesystem::path atlas_names_path(const std::filesystem::path& atlas) {
  std::filesystem::path p = atlas;
  if (p.extension() == ".gz") p.replace_extension();  // aal.nii.gz -> aal.nii
  p += ".txt";
  return p;
}

std::map<int, std::string> parse_atlas_names(const std::string& text) {
  std::map<int, std::string> names;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream fields(line);
    int index = 0;
    std::string name;
    if (fields >> index >> name) names[index] = name;
  }
  return names;
}

LabelAtlas read_label_atlas(const std::filesystem::path& path) {
  NiftiVolume nifti = read_nifti_volume(path);
  LabelAtlas atlas;
  atlas.source = path.string();
  atlas.labels.grid = nifti.volume.grid;
  atlas.labels.values.resize(nifti.volume.values.size());
  for (std::size_t v = 0; v < nifti.volume.values.size(); ++v) {
    const float x = nifti.volume.values[v];
    // Labels are integers; a scan given by mistake has fractional or huge values.
    if (x != std::round(x) || std::abs(x) > 1e6f)
      throw std::runtime_error(path.string() + ": not a label atlas (voxel value " +
                               std::to_string(x) + " is not a region index)");
    atlas.labels.values[v] = static_cast<std::int32_t>(x);
  }
  std::ifstream names(atlas_names_path(path));
  if (names) {
    std::stringstream text;
    text << names.rdbuf();
    atlas.names = parse_atlas_names(text.str());
  }
  return atlas;
}

}  // namespace dynamesh
