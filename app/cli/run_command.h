// `dynamesh-cli run`: builds the scene, adapts over time, writes what was asked for.
#pragma once

#include <iosfwd>

#include "app/cli/run_options.h"

namespace dynamesh {

// Returns the exit status. Throws UsageError for bad input found while setting up (unknown
// scene, unwritable output, ...).
int run_command(const RunOptions& options, std::ostream& out, std::ostream& log);

}  // namespace dynamesh
