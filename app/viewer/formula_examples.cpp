#include "app/viewer/formula_examples.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "app/viewer/viewer_args.h"

namespace dynamesh {
namespace {

namespace fs = std::filesystem;

// `file` as written in an .args file in `dir`: next to it, else against each directory
// above it (the file's own view, then the repository root's), else as written.
std::string resolve_beside(const std::string& file, const fs::path& dir) {
  const fs::path written(file);
  if (written.is_absolute()) return file;
  std::error_code error;
  for (fs::path base = dir;; base = base.parent_path()) {
    const fs::path candidate = base / written;
    if (fs::is_regular_file(candidate, error)) return candidate.lexically_normal().string();
    if (base == base.parent_path() || base.empty()) break;
  }
  return file;
}

std::string executable_dir() {
  std::error_code error;
  const fs::path exe = fs::read_symlink("/proc/self/exe", error);
  return error ? std::string() : exe.parent_path().string();
}

}  // namespace

FormulaExample load_formula_example(const std::string& path) {
  FormulaExample e;
  e.path = path;
  e.name = fs::path(path).stem().string();
  std::ifstream in(path);
  if (!in) {
    e.error = "cannot read " + path;
    return e;
  }
  std::vector<std::string> words;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();  // written on Windows
    if (!line.empty()) words.push_back(line);
  }
  try {
    const ViewerArgs args = parse_viewer_args(words);
    if (args.state.controls.scene != "expr") {
      e.error = path + ": not an expr scene (--scene expr missing)";
      return e;
    }
    e.text = args.state.controls.scene_text;
  } catch (const std::exception& error) {
    e.error = path + ": " + error.what();
    return e;
  }
  const fs::path dir = fs::absolute(fs::path(path)).parent_path();
  for (auto& [key, value] : e.text)
    if (key == "base-mesh") value = resolve_beside(value, dir);
  return e;
}

std::vector<FormulaExample> load_formula_examples(const std::string& dir) {
  std::vector<std::string> files;
  std::error_code error;
  for (fs::directory_iterator it(dir, error), end; !error && it != end; it.increment(error))
    if (it->path().extension() == ".args") files.push_back(it->path().string());
  std::sort(files.begin(), files.end());
  std::vector<FormulaExample> examples;
  for (const std::string& file : files) examples.push_back(load_formula_example(file));
  return examples;
}

std::vector<std::string> examples_dir_candidates() {
  std::vector<std::string> dirs;
  if (const char* assets = std::getenv("DYNAMESH_ASSETS"); assets != nullptr && *assets != '\0')
    dirs.push_back((fs::path(assets) / "examples").string());
  if (const std::string exe = executable_dir(); !exe.empty()) {
    dirs.push_back((fs::path(exe) / "assets" / "examples").string());
    dirs.push_back((fs::path(exe).parent_path() / "assets" / "examples").string());
    dirs.push_back(
        (fs::path(exe).parent_path() / "share" / "dynamesh" / "assets" / "examples").string());
  }
#ifdef DYNAMESH_ASSETS_DIR
  dirs.push_back((fs::path(DYNAMESH_ASSETS_DIR) / "examples").string());
#endif
  return dirs;
}

std::string find_examples_dir() {
  std::error_code error;
  for (const std::string& dir : examples_dir_candidates())
    if (fs::is_directory(dir, error)) return dir;
  return {};
}

}  // namespace dynamesh
