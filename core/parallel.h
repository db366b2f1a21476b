// Loops shorter than this run on one thread: a parallel region costs more than it saves
// below a few thousand cheap iterations, and much more when the cores are busy.
#pragma once

#include <cstdint>

namespace dynamesh {

inline constexpr std::int64_t kParallelMin = 4096;

}  // namespace dynamesh
