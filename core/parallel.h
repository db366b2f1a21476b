// Threading policy of the engine (OpenMP).
//
// Loops shorter than kParallelMin run on one thread: a parallel region costs more than it
// saves below a few thousand cheap iterations, and much more when the cores are busy.
//
// A desktop is never idle (the viewer's own renderer competes with the adapter), and
// libgomp's default is to let a thread that reaches a barrier spin for a long while before
// it sleeps. With one other busy thread on a 2-core machine that spinning thread takes the
// core the late thread needs, and a sphere step went from 3.7 ms to 64 ms (issue 17). Every
// program that links the engine therefore starts OpenMP with a passive wait policy (idle
// threads sleep at once), unless the user set OMP_WAIT_POLICY or GOMP_SPINCOUNT
// themselves. libgomp reads its environment when it is loaded, before main() and before any
// static constructor of ours, and a variable set from the executable's .preinit_array (which
// the dynamic loader runs first) does not reach it: glibc's environment is not set up yet
// there. So parallel.cpp's .preinit_array entry executes the program once more with the
// variable added (DYNAMESH_OMP_WAIT_POLICY=engine marks it as the engine's). engine_wait_policy()
// reports what libgomp was given (and, being referenced from the Adapter, keeps that object file
// in every program that adapts meshes).
#pragma once

#include <omp.h>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace dynamesh {

inline constexpr std::int64_t kParallelMin = 4096;
// The same for loops whose every iteration costs microseconds (measuring a face: a dozen and
// more surface evaluations). With kParallelMin, the ~2,200 faces a twist step measures (15,000
// triangles, predictive sampling) were measured on one thread while the other slept.
inline constexpr std::int64_t kParallelMinCostly = 64;

// "passive" when the engine chose the policy; "user" when the user's OMP_WAIT_POLICY or
// GOMP_SPINCOUNT decide it; "default" when the engine could not set it (libgomp's own: workers
// spin a few milliseconds after each parallel loop), as under valgrind.
const char* engine_wait_policy();

// An order-keeping parallel filter, for the step's scans over every face or vertex slot whose
// few hits feed a serial pass (a queue, a list to measure) that must see them in slot order:
// the same items in the same order as the serial loop, whatever the thread count. Slots are
// cut into fixed blocks taken dynamically (a thread that the machine's other load delays holds
// up one block, not half the slots); each block keeps its hits in its own list, and the lists
// are joined in block order. The lists are kept between calls: no allocation per step once
// they have grown. At 10^6 triangles these scans ran on one thread while the other waited
// (issue 17's profile of the capsule-bend step).
template <class T>
class OrderedCollector {
 public:
  // Sets `out` to the items of every i in [0, n) for which keep(i, item) returns true (it
  // fills `item` then), in the order of i. keep runs in parallel above kParallelMin slots.
  template <class Keep>
  void collect(std::int64_t n, std::vector<T>& out, Keep keep) {
    out.clear();
    T item{};
    if (n <= kParallelMin) {
      for (std::int64_t i = 0; i < n; ++i)
        if (keep(i, item)) out.push_back(item);
      return;
    }
    const std::int64_t block = block_size(n);
    const std::int64_t blocks = (n + block - 1) / block;
    if (parts_.size() < static_cast<std::size_t>(blocks))
      parts_.resize(static_cast<std::size_t>(blocks));
#pragma omp parallel for schedule(dynamic, 1) firstprivate(item)
    for (std::int64_t b = 0; b < blocks; ++b) {
      std::vector<T>& part = parts_[static_cast<std::size_t>(b)];
      part.clear();
      const std::int64_t end = std::min(n, (b + 1) * block);
      for (std::int64_t i = b * block; i < end; ++i)
        if (keep(i, item)) part.push_back(item);
    }
    for (std::int64_t b = 0; b < blocks; ++b) {
      const std::vector<T>& part = parts_[static_cast<std::size_t>(b)];
      out.insert(out.end(), part.begin(), part.end());
    }
  }

 private:
  // Blocks of at most kMaxBlock slots, and at least kMinBlocks of them down to kMinBlock slots
  // each: with blocks of 16384 alone, every scan of a mesh under 16384 elements was one block,
  // on one thread (a twist step at 15,000 triangles: the weld pass's candidates, 1.9 ms of
  // its 2.8 ms weld phase, took as long on two threads as on one). The blocks do not change
  // the items or their order, only how the work is dealt out.
  static constexpr std::int64_t kMaxBlock = 16384, kMinBlock = 256, kMinBlocks = 16;
  static std::int64_t block_size(std::int64_t n) {
    return std::clamp(n / kMinBlocks, kMinBlock, kMaxBlock);
  }
  std::vector<std::vector<T>> parts_;
};

}  // namespace dynamesh
