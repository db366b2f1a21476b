// Mesh48: a conforming semi-regular 4-8 triangle mesh with the stellar operators edge split
// and vertex weld (Velho's 4-8 meshes; de Goes et al. 2006, Section 3.2).
//
// Storage is index based with free lists, so a vertex or face id is stable while the element
// lives (until renumber(), which tells the listeners) and no operation allocates once
// capacity is reached. Every face stores its vertices
// counter-clockwise with its *newest* vertex first: local edge 0 (from vertex 1 to vertex 2)
// is its refinement edge. Each face knows the twin halfedge across each of its edges and its
// depth (number of bisections since the base mesh); each split-born vertex knows its parent
// edge and level.
//
// Per-element data kept outside the mesh (samples, colours, ...) follows splits, welds and
// renumberings through MeshListener: one callback per operation, carrying which face slots
// were bisected or merged, and how, or every slot's new id.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/geometry/vector_types.h"
#include "core/mesh/handles.h"
#include "core/mesh/renumbering.h"

namespace dynamesh {

// One face bisected into two (split) or two faces merged back into one (weld). The parent
// triangle (apex, a, b) has its refinement edge (a, b) cut at the new vertex m:
//   children[0] = (m, apex, a)   (reuses the parent's slot: children[0] == parent)
//   children[1] = (m, b, apex)
// A point with barycentric coordinates (c_apex, c_a, c_b) in the parent lies in
// children[0] when c_a >= c_b, with coordinates (2 c_b, c_apex, c_a - c_b), else in
// children[1] with coordinates (2 c_a, c_b - c_a, c_apex).
struct Bisection {
  Face parent;
  std::array<Face, 2> children;
  std::array<Vertex, 3> parent_vertices;  // (apex, a, b)
};

// What a split created or a weld removed: the vertex m on the edge (parents[0], parents[1])
// and the one (boundary edge) or two bisections around it.
struct DiamondChange {
  Vertex vertex;
  std::array<Vertex, 2> parents;
  int count = 0;
  std::array<Bisection, 2> halves;
};

class Mesh48;

// Observer of structural changes. after_split is called once the new faces and vertex exist
// (the vertex is placed at the midpoint of its parents; a listener may move it).
// after_weld is called once the merged faces exist; the removed vertex's and freed faces'
// slots are dead but their ids are still those in the record.
// after_renumber is called once the mesh uses the new ids: everything a listener keeps per
// vertex or face slot must move to them (renumber_elements); there is no default, so that
// no listener can forget.
class MeshListener {
 public:
  virtual ~MeshListener() = default;
  virtual void after_split(Mesh48& mesh, const DiamondChange& change) = 0;
  virtual void after_weld(Mesh48& mesh, const DiamondChange& change) = 0;
  virtual void after_renumber(Mesh48& mesh, const Renumbering& renumbering) = 0;
};

// A vertex's place in one face: face.vertex(local) == that vertex.
struct Corner {
  Face face;
  int local = 0;
};

// What check() found: empty problems means the mesh satisfies every invariant.
struct CheckReport {
  std::vector<std::string> problems;
  bool ok() const { return problems.empty(); }
  std::string summary(std::size_t max_lines = 10) const;
};

class Mesh48 {
 public:
  Mesh48() = default;

  // Builds a base mesh from triangles that form a triangulated quadrangulation: each
  // triangle is given newest vertex first, (apex, a, b), and its refinement edge (a, b) is
  // shared with a triangle that has the same refinement edge, or lies on the boundary.
  // Throws std::invalid_argument (with what is wrong and where) on non-manifold input,
  // inconsistent orientation, or unpaired refinement edges.
  static Mesh48 from_base_triangles(std::vector<Vec3> positions, std::vector<Vec2> uvs,
                                    const std::vector<std::array<std::uint32_t, 3>>& triangles);

  // --- sizes and liveness ----------------------------------------------------------------
  std::size_t n_vertices() const { return n_live_vertices_; }
  std::size_t n_faces() const { return n_live_faces_; }
  // Upper bounds of ids (for sizing per-element arrays indexed by id).
  std::size_t vertex_capacity() const { return vertex_face_.size(); }
  std::size_t face_capacity() const { return faces_.size(); }
  bool is_alive(Vertex v) const { return vertex_face_[v.idx] != kInvalidIndex; }
  bool is_alive(Face f) const { return faces_[f.idx].v[0] != kInvalidIndex; }
  void reserve(std::size_t vertices, std::size_t faces);

  // --- faces -----------------------------------------------------------------------------
  Vertex vertex(Face f, int local) const { return Vertex(faces_[f.idx].v[local]); }
  std::array<Vertex, 3> vertices(Face f) const;
  Vertex newest_vertex(Face f) const { return vertex(f, 0); }
  int depth(Face f) const { return faces_[f.idx].depth; }
  // Across local edge i; invalid on the boundary.
  Halfedge twin(Halfedge h) const { return Halfedge(faces_[h.face().idx].twin[h.local()]); }
  Face neighbor(Face f, int local_edge) const;
  bool is_boundary(Halfedge h) const { return !twin(h).is_valid(); }
  Vertex from_vertex(Halfedge h) const { return vertex(h.face(), (h.local() + 1) % 3); }
  Vertex to_vertex(Halfedge h) const { return vertex(h.face(), (h.local() + 2) % 3); }
  // True when the face's refinement edge is its neighbour's refinement edge too (a diamond),
  // or lies on the boundary: splitting it then touches no other face.
  bool is_paired(Face f) const;

  // --- vertices --------------------------------------------------------------------------
  const Vec3& position(Vertex v) const { return positions_[v.idx]; }
  Vec3& position(Vertex v) { return positions_[v.idx]; }
  const Vec2& uv(Vertex v) const { return uvs_[v.idx]; }
  Vec2& uv(Vertex v) { return uvs_[v.idx]; }
  // Indexed by vertex id (dead slots included): for parallel loops over all vertices.
  std::vector<Vec3>& positions() { return positions_; }
  const std::vector<Vec3>& positions() const { return positions_; }
  std::vector<Vec2>& uvs() { return uvs_; }
  const std::vector<Vec2>& uvs() const { return uvs_; }
  bool is_base(Vertex v) const { return lineage_[v.idx].parent_a == kInvalidIndex; }
  std::array<Vertex, 2> parents(Vertex v) const {
    return {Vertex(lineage_[v.idx].parent_a), Vertex(lineage_[v.idx].parent_b)};
  }
  int level(Vertex v) const { return lineage_[v.idx].level; }
  Corner corner(Vertex v) const;
  bool is_boundary(Vertex v) const;
  int valence(Vertex v) const;  // number of neighbouring vertices

  // Visits the faces around v in counter-clockwise order (starting at the boundary for a
  // boundary vertex) as fn(Corner).
  template <class Fn>
  void for_each_corner_around(Vertex v, Fn&& fn) const;
  // Neighbouring vertices in counter-clockwise order; cleared first.
  void one_ring(Vertex v, std::vector<Vertex>& ring) const;
  void incident_faces(Vertex v, std::vector<Face>& faces) const;

  // --- live elements ---------------------------------------------------------------------
  std::vector<Vertex> live_vertices() const;
  std::vector<Face> live_faces() const;

  // --- stellar operators -----------------------------------------------------------------
  // Bisects the refinement edge of f (and of its neighbour across it), first splitting the
  // neighbour recursively when the edge is not the neighbour's refinement edge, so that the
  // mesh stays conforming. Returns the new vertex, or an invalid handle (and changes
  // nothing) when f is already kMaxDepth bisections deep: a runaway refinement (e.g. at a
  // fold of the surface) stops there instead of overflowing.
  Vertex split(Face f);
  static constexpr int kMaxDepth = 250;
  // True when v is split-born, the newest vertex of every incident face and has 4 of them
  // (2 on the boundary): welding it exactly undoes the split that created it.
  bool can_weld(Vertex v) const;
  // Removes v and restores its parent edge; returns false (and changes nothing) when
  // !can_weld(v).
  bool weld(Vertex v);
  // What weld(v) would do, without doing it: fills `change` (each half's parent slot, its
  // children and the parent triangle's vertices) and returns true when v can be welded.
  bool plan_weld(Vertex v, DiamondChange& change) const;

  // --- surgery (issue 16, local repair of a topology change) -----------------------------
  // Replaces the faces `removed` by `triangles`, given newest vertex first over the vertices
  // `corners` (an index i < existing.size() is the live vertex existing[i], otherwise the new
  // vertex made at positions[i - existing.size()]). The new triangles must close the hole
  // exactly (each of their unshared edges is the reverse of an edge of a remaining face whose
  // neighbour was removed) and keep the 4-8 rule across the border (`depths`, one per
  // triangle; empty means all 0): a shared edge that is a leg of both sides joins faces alike
  // deep; a triangle's refinement edge there is either the remaining face's refinement edge
  // too (alike deep) or its leg (one bisection coarser, a half diamond). Vertices used by no
  // face any more die; vertices on the border, and those whose parents died, become base
  // vertices (their welds would restore edges that no longer exist). No listener is told:
  // the caller re-synchronises what it keeps per element. Returns the new vertices' ids.
  // Throws std::logic_error when the triangles do not close the hole as described (the mesh
  // is then unchanged) or leave a vertex with two fans (found afterwards: the mesh is then
  // unusable, so keep a copy).
  std::vector<Vertex> replace_region(const std::vector<Face>& removed,
                                     const std::vector<Vertex>& existing,
                                     const std::vector<Vec3>& positions,
                                     const std::vector<std::array<std::uint32_t, 3>>& triangles,
                                     const std::vector<int>& depths = {});

  // --- renumbering ---------------------------------------------------------------------
  // Gives every live vertex and face the id `renumbering` assigns it (a bijection onto
  // 0..n-1: spatial_order.h makes one), compacting the free slots away, and tells the
  // listeners. Geometry, connectivity, depths and lineage are unchanged, only their ids.
  // Throws std::invalid_argument (the mesh unchanged) when it is not such a bijection.
  void renumber(const Renumbering& renumbering);

  // --- listeners -------------------------------------------------------------------------
  void add_listener(MeshListener* listener);
  void remove_listener(MeshListener* listener);
  // Forgets every listener: a copy made for trial surgery (local_repair.h) must not tell the
  // original's listeners about its splits.
  void clear_listeners() { listeners_.clear(); }

  // --- invariants ------------------------------------------------------------------------
  // Full invariant check, O(mesh): conforming and edge-manifold (every halfedge's twin
  // runs the other way between the same vertices), consistent orientation, symmetric
  // neighbour links, 4-8 structure (the face across a refinement edge shares it or is one
  // bisection coarser), parent edges consistent, valences of split-born vertices in [4, 8]
  // (interior) or [3, 5] (boundary), weldable vertices with all neighbours of lower level,
  // and the bookkeeping (live counts, free lists, vertex corners).
  CheckReport check() const;

 private:
  struct FaceRecord {
    std::uint32_t v[3];
    std::uint32_t twin[3];
    std::uint8_t depth;
  };

  std::uint32_t allocate_face();
  std::uint32_t allocate_vertex();
  void set_face(std::uint32_t f, std::uint32_t a, std::uint32_t b, std::uint32_t c,
                std::uint8_t depth);
  void link(std::uint32_t face_a, int local_a, std::uint32_t halfedge_b);
  void bisect_half(Bisection& half, std::uint32_t m);
  Vertex split_diamond(Face f);
  int collect_weld_star(Vertex v, std::array<Corner, 4>& star) const;
  void apply_weld(const DiamondChange& change);
  void notify_split(const DiamondChange& change);
  void notify_weld(const DiamondChange& change);
  // Corner of v in the face across the edge that leaves f at corner (f, local)
  // clockwise / counter-clockwise around v; invalid face on the boundary.
  Corner rotate_cw(Corner c) const;
  Corner rotate_ccw(Corner c) const;
  Corner first_corner_ccw(Vertex v) const;  // the boundary-most corner for a boundary vertex

  std::vector<FaceRecord> faces_;
  std::vector<Vec3> positions_;
  std::vector<Vec2> uvs_;
  // One face holding each vertex (its local index is found by comparison, so a split or weld
  // only rewrites the entries of vertices that left a face); kInvalidIndex when dead.
  std::vector<std::uint32_t> vertex_face_;
  // Parent edge and level of each vertex, together: a split writes them at once.
  struct Lineage {
    std::uint32_t parent_a = kInvalidIndex, parent_b = kInvalidIndex;
    std::uint8_t level = 0;
  };
  std::vector<Lineage> lineage_;
  bool has_uvs_ = false;  // the base mesh came with (u, v): splits interpolate them
  std::vector<std::uint32_t> free_faces_, free_vertices_;
  std::size_t n_live_vertices_ = 0, n_live_faces_ = 0;
  std::vector<MeshListener*> listeners_;
};

// --- inline traversal ----------------------------------------------------------------------

inline Corner Mesh48::corner(Vertex v) const {
  const std::uint32_t f = vertex_face_[v.idx];
  const auto& r = faces_[f].v;
  return {Face(f), r[0] == v.idx ? 0 : (r[1] == v.idx ? 1 : (r[2] == v.idx ? 2 : -1))};
}

inline Corner Mesh48::rotate_ccw(Corner c) const {
  // f = (v, a, b): the next face counter-clockwise shares edge (b -> v), local edge c+1.
  const std::uint32_t t = faces_[c.face.idx].twin[(c.local + 1) % 3];
  if (t == kInvalidIndex) return {Face(), 0};
  return {Face(t / 3), static_cast<int>((t % 3 + 1) % 3)};
}

inline Corner Mesh48::rotate_cw(Corner c) const {
  // f = (v, a, b): the previous face shares edge (v -> a), local edge c+2.
  const std::uint32_t t = faces_[c.face.idx].twin[(c.local + 2) % 3];
  if (t == kInvalidIndex) return {Face(), 0};
  return {Face(t / 3), static_cast<int>((t % 3 + 2) % 3)};
}

inline Corner Mesh48::first_corner_ccw(Vertex v) const {
  const Corner start = corner(v);
  Corner c = start;
  for (;;) {
    const Corner prev = rotate_cw(c);
    if (!prev.face.is_valid() || prev.face == start.face) return c;
    c = prev;
  }
}

template <class Fn>
void Mesh48::for_each_corner_around(Vertex v, Fn&& fn) const {
  const Corner first = first_corner_ccw(v);
  Corner c = first;
  do {
    fn(c);
    c = rotate_ccw(c);
  } while (c.face.is_valid() && c.face != first.face);
}

inline Face Mesh48::neighbor(Face f, int local_edge) const {
  const std::uint32_t t = faces_[f.idx].twin[local_edge];
  return t == kInvalidIndex ? Face() : Face(t / 3);
}

inline std::array<Vertex, 3> Mesh48::vertices(Face f) const {
  const auto& r = faces_[f.idx];
  return {Vertex(r.v[0]), Vertex(r.v[1]), Vertex(r.v[2])};
}

inline bool Mesh48::is_paired(Face f) const {
  const std::uint32_t t = faces_[f.idx].twin[0];
  return t == kInvalidIndex || t % 3 == 0;
}

}  // namespace dynamesh
