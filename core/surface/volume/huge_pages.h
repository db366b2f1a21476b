// Full-grid buffers of the volume pipeline (a 181 x 217 x 181 volume is 7.1 M voxels: 28 MB
// per float array) are mapped afresh by malloc for every stage and given back when freed
// (allocator_policy.h), so each stage faults its arrays in again, one 4 KiB page at a time.
// On the VMs this runs on a page fault costs microseconds: measured, faults and the zeroing
// around them took 30% of the mri preparation's CPU time. Asking the kernel for transparent
// huge pages (2 MiB) on those arrays before they are touched makes that 512 times fewer
// faults; where THP is off ("never") the advice is ignored and nothing changes.
#pragma once

#include <cstddef>
#include <vector>

namespace dynamesh {

// madvise(MADV_HUGEPAGE) on the 2 MiB-aligned part of [data, data + bytes); a no-op for
// small ranges and where the call is unsupported.
void advise_huge_pages(void* data, std::size_t bytes);

// v.reserve(n) with huge pages advised on the new storage before anything touches it.
template <class T>
void reserve_huge(std::vector<T>& v, std::size_t n) {
  if (v.capacity() >= n) return;
  std::vector<T>().swap(v);
  v.reserve(n);
  advise_huge_pages(v.data(), n * sizeof(T));
}

}  // namespace dynamesh
