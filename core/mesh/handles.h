// Typed index handles for the 4-8 mesh (pmp-library style): a handle is an index into the
// mesh's arrays, cheap to copy, and invalid when it holds kInvalidIndex.
#pragma once

#include <compare>
#include <cstdint>
#include <functional>

namespace dynamesh {

inline constexpr std::uint32_t kInvalidIndex = 0xffffffffu;

template <class Tag>
struct Handle {
  std::uint32_t idx = kInvalidIndex;

  constexpr Handle() = default;
  constexpr explicit Handle(std::uint32_t i) : idx(i) {}
  constexpr bool is_valid() const { return idx != kInvalidIndex; }
  constexpr auto operator<=>(const Handle&) const = default;
};

struct VertexTag {};
struct FaceTag {};

using Vertex = Handle<VertexTag>;
using Face = Handle<FaceTag>;

// A halfedge is a (face, local edge) pair packed as 3 * face + local. Local edge i of a face
// is the edge opposite its vertex i, running from vertex i+1 to vertex i+2 (counter-clockwise).
struct Halfedge {
  std::uint32_t idx = kInvalidIndex;

  constexpr Halfedge() = default;
  constexpr explicit Halfedge(std::uint32_t i) : idx(i) {}
  constexpr Halfedge(Face f, int local) : idx(3 * f.idx + static_cast<std::uint32_t>(local)) {}
  constexpr bool is_valid() const { return idx != kInvalidIndex; }
  constexpr Face face() const { return Face(idx / 3); }
  constexpr int local() const { return static_cast<int>(idx % 3); }
  constexpr auto operator<=>(const Halfedge&) const = default;
};

}  // namespace dynamesh

template <class Tag>
struct std::hash<dynamesh::Handle<Tag>> {
  std::size_t operator()(dynamesh::Handle<Tag> h) const noexcept { return h.idx; }
};
