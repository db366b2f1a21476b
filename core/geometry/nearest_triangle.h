// The triangle of a fixed set nearest to a query point, through a uniform grid of buckets
// (each triangle listed in every cell its bounding box overlaps; a query visits shells of
// cells around its own until no unvisited cell can hold anything nearer). Answers exactly what
// a plain search over every triangle answers, ties included (the lowest index), so a caller
// can switch to it without changing a result. Immutable after construction: queries are
// reentrant and thread-safe.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/geometry/vector_types.h"

namespace dynamesh {

// The point of the triangle abc nearest to p.
Vec3 nearest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

class NearestTriangleIndex {
 public:
  static constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();

  struct Hit {
    std::size_t triangle = kNone;  // kNone: none within the search's reach
    double squared_distance = std::numeric_limits<double>::infinity();
  };

  NearestTriangleIndex() = default;
  explicit NearestTriangleIndex(std::vector<std::array<Vec3, 3>> triangles);

  // The nearest triangle to p (the lowest index among equally near ones), if one lies within
  // `reach` of it; kNone otherwise.
  Hit nearest(const Vec3& p, double reach = std::numeric_limits<double>::infinity()) const;

  std::size_t size() const { return triangles_.size(); }

 private:
  using Cell = std::array<int, 3>;
  Cell cell_of(const Vec3& p) const;
  std::size_t cell_index(const Cell& c) const;
  // Checks the triangles listed in cell c against the best hit so far.
  void visit(const Cell& c, const Vec3& p, Hit& best) const;

  std::vector<std::array<Vec3, 3>> triangles_;
  Box3 box_;
  double cell_size_ = 1.0;
  Cell cells_{{0, 0, 0}};
  std::vector<std::uint32_t> first_;  // per cell, into listed_ (one past the end last)
  std::vector<std::uint32_t> listed_;
};

}  // namespace dynamesh
