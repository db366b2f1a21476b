// The formula panel's library of examples: assets/examples/*.args, each the arguments of one
// `dynamesh-cli run` (or `dynamesh`) command, one per line. They are read as the viewer's own
// command line is (parse_viewer_args), so a file that runs from the shell loads in the panel.
// Read once at start (a handful of small files); nothing here runs while a frame is drawn.
#pragma once

#include <string>
#include <vector>

#include "core/surface/scene_registry.h"

namespace dynamesh {

struct FormulaExample {
  std::string name;  // the file's stem, "breathing-torus"
  std::string path;
  TextOptions text;   // its scene text options, a relative --base-mesh made absolute
  std::string error;  // non-empty: the file could not be used, and why
};

// One .args file. A relative --base-mesh is looked for next to the file and then against
// each directory above it, so "torus.obj" and "assets/examples/torus.obj" (the repository
// root's view) both work from any working directory; found, it becomes absolute.
FormulaExample load_formula_example(const std::string& path);
// Every *.args file of `dir`, by name. None (or no such directory): empty.
std::vector<FormulaExample> load_formula_examples(const std::string& dir);

// Where the examples are: the first directory that exists of $DYNAMESH_ASSETS/examples,
// assets/examples next to the executable, one level above it (a build directory inside the
// source tree), ../share/dynamesh/assets/examples (installed), and the source tree the
// executable was built from. Empty when none exists.
std::string find_examples_dir();
// The candidates above, in that order (for messages and tests).
std::vector<std::string> examples_dir_candidates();

}  // namespace dynamesh
