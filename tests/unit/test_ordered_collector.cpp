// OrderedCollector (core/parallel.h): the items the serial loop would list, in its order,
// whatever the thread count and however the blocks are shared out.
#include <gtest/gtest.h>
#include <omp.h>

#include <cstdint>
#include <vector>

#include "core/parallel.h"

namespace dynamesh {
namespace {

bool kept(std::int64_t i, std::int64_t n) {
  return i % 7 == 0 || i == n - 1;
}

TEST(OrderedCollector, ListsTheSerialLoopsItemsInItsOrder) {
  const int threads_before = omp_get_max_threads();
  OrderedCollector<std::int64_t> collector;
  std::vector<std::int64_t> out;
  // Below kParallelMin (serial), just above it (blocks of the smallest size), between that and
  // the largest block (blocks of n / 16), across many blocks, and smaller again (the block
  // lists kept from the larger call must not leak into the smaller one).
  for (const std::int64_t n : {std::int64_t{1000}, kParallelMin + 1, std::int64_t{12'345},
                               std::int64_t{1'000'003}, std::int64_t{50'000}}) {
    std::vector<std::int64_t> want;  // the serial loop's list (items other than the indices)
    for (std::int64_t i = 0; i < n; ++i)
      if (kept(i, n)) want.push_back(3 * i);
    for (const int threads : {1, 2, 4}) {
      omp_set_num_threads(threads);
      collector.collect(n, out, [n](std::int64_t i, std::int64_t& item) {
        item = 3 * i;
        return kept(i, n);
      });
      EXPECT_EQ(out, want) << "n " << n << ", " << threads << " threads";
    }
  }
  omp_set_num_threads(threads_before);
}

TEST(OrderedCollector, EmptyWhenNothingIsKept) {
  OrderedCollector<std::int64_t> collector;
  std::vector<std::int64_t> out{1, 2, 3};
  collector.collect(100'000, out, [](std::int64_t, std::int64_t&) { return false; });
  EXPECT_TRUE(out.empty());
}

}  // namespace
}  // namespace dynamesh
