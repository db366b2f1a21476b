// Memory policy of the engine: large blocks go back to the system when they are freed.
//
// The engine's big buffers follow the mesh: the sample pool of the default sphere holds
// 1.6M samples (19 MB, and the pool may be twice that before it is compacted) at R = 9 and
// 17k at R = 0.6, and SampleStore gives its buffers back when the mesh shrinks. glibc's
// malloc puts a block in its own mapping (returned to the system by free) only above a
// threshold that it raises, up to 32 MB, to the size of every mapped block freed; after the
// first shrink the pool's next buffers therefore came from the heap, which is only given
// back from its top. Measured on the sphere going 0 -> 1 -> 0 four times (issue 15's soak):
// with that dynamic threshold the resident memory at t = 0 went 105 -> 119 MB over three
// cycles (53 MB of freed heap kept resident, reused in a different order each cycle); with
// a fixed threshold it stays at 72-73 MB.
//
// So every program that links the engine starts with glibc's thresholds fixed: blocks of
// kMmapThreshold and more are mapped on their own, and the free top of the heap is given back
// above glibc's default trim threshold (128 kB). (Keeping 8 MB of free heap top instead let
// the resident memory at t = 0 creep up by 2 MB a cycle: 77.7, 79.6, 79.6, 81.5 MB at steps
// 1000-4000 of the soak.) A user's own setting (MALLOC_MMAP_THRESHOLD_,
// MALLOC_TRIM_THRESHOLD_ or GLIBC_TUNABLES) is kept. engine_allocator_policy() reports what
// was chosen (and, referenced from SampleStore, keeps this object file in every program that
// adapts meshes).
#pragma once

#include <cstddef>

namespace dynamesh {

inline constexpr std::size_t kMmapThreshold = std::size_t{4} << 20;

// "fixed thresholds" when the engine set them; "user" when the environment set malloc's
// thresholds; "default" on a C library other than glibc or when setting them failed.
const char* engine_allocator_policy();

}  // namespace dynamesh
