// Mesh48 storage, construction and the stellar operators split and weld.
#include "core/mesh/mesh48.h"

#include <algorithm>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

namespace dynamesh {
namespace {

constexpr int next(int i) {
  return i == 2 ? 0 : i + 1;
}
constexpr int prev(int i) {
  return i == 0 ? 2 : i - 1;
}

std::uint64_t edge_key(std::uint32_t from, std::uint32_t to) {
  return (static_cast<std::uint64_t>(from) << 32) | to;
}

}  // namespace

std::string CheckReport::summary(std::size_t max_lines) const {
  if (ok()) return "ok";
  std::ostringstream out;
  out << problems.size() << " problem(s):";
  for (std::size_t i = 0; i < problems.size() && i < max_lines; ++i) out << "\n  " << problems[i];
  return out.str();
}

// --- storage -----------------------------------------------------------------------------

void Mesh48::reserve(std::size_t vertices, std::size_t faces) {
  faces_.reserve(faces);
  positions_.reserve(vertices);
  uvs_.reserve(vertices);
  vertex_face_.reserve(vertices);
  lineage_.reserve(vertices);
}

std::uint32_t Mesh48::allocate_face() {
  ++n_live_faces_;
  if (!free_faces_.empty()) {
    const std::uint32_t f = free_faces_.back();
    free_faces_.pop_back();
    return f;
  }
  faces_.push_back({});
  return static_cast<std::uint32_t>(faces_.size() - 1);
}

std::uint32_t Mesh48::allocate_vertex() {
  ++n_live_vertices_;
  if (!free_vertices_.empty()) {
    const std::uint32_t v = free_vertices_.back();
    free_vertices_.pop_back();
    return v;
  }
  positions_.emplace_back(Vec3::Zero());
  uvs_.emplace_back(Vec2::Zero());
  vertex_face_.push_back(kInvalidIndex);
  lineage_.emplace_back();
  return static_cast<std::uint32_t>(positions_.size() - 1);
}

void Mesh48::set_face(std::uint32_t f, std::uint32_t a, std::uint32_t b, std::uint32_t c,
                      std::uint8_t depth) {
  FaceRecord& r = faces_[f];
  r.v[0] = a;
  r.v[1] = b;
  r.v[2] = c;
  r.depth = depth;
}

void Mesh48::link(std::uint32_t face_a, int local_a, std::uint32_t halfedge_b) {
  faces_[face_a].twin[local_a] = halfedge_b;
  if (halfedge_b != kInvalidIndex)
    faces_[halfedge_b / 3].twin[halfedge_b % 3] = 3 * face_a + local_a;
}

// --- construction ------------------------------------------------------------------------

Mesh48 Mesh48::from_base_triangles(std::vector<Vec3> positions, std::vector<Vec2> uvs,
                                   const std::vector<std::array<std::uint32_t, 3>>& triangles) {
  const std::size_t nv = positions.size();
  const bool has_uvs = !uvs.empty();
  if (uvs.empty()) uvs.assign(nv, Vec2::Zero());
  if (uvs.size() != nv)
    throw std::invalid_argument("base mesh: uv count differs from vertex count");
  if (triangles.empty()) throw std::invalid_argument("base mesh: no triangles");

  Mesh48 mesh;
  mesh.has_uvs_ = has_uvs;
  mesh.positions_ = std::move(positions);
  mesh.uvs_ = std::move(uvs);
  mesh.vertex_face_.assign(nv, kInvalidIndex);
  mesh.lineage_.assign(nv, Lineage{});
  mesh.faces_.resize(triangles.size());

  std::unordered_map<std::uint64_t, std::uint32_t> halfedge_of;
  halfedge_of.reserve(3 * triangles.size());
  for (std::uint32_t f = 0; f < triangles.size(); ++f) {
    const auto& t = triangles[f];
    for (int i = 0; i < 3; ++i) {
      if (t[i] >= nv) {
        throw std::invalid_argument("base mesh: triangle " + std::to_string(f) +
                                    " refers to vertex " + std::to_string(t[i]) + " of " +
                                    std::to_string(nv));
      }
    }
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
      throw std::invalid_argument("base mesh: triangle " + std::to_string(f) + " repeats a vertex");
    }
    mesh.set_face(f, t[0], t[1], t[2], 0);
    for (std::uint32_t v : t) mesh.vertex_face_[v] = f;
    for (int i = 0; i < 3; ++i) {
      const auto [it, fresh] = halfedge_of.emplace(edge_key(t[next(i)], t[prev(i)]), 3 * f + i);
      if (!fresh) {
        throw std::invalid_argument("base mesh: edge (" + std::to_string(t[next(i)]) + ", " +
                                    std::to_string(t[prev(i)]) +
                                    ") is used twice in the same direction: the mesh is "
                                    "non-manifold or inconsistently oriented");
      }
    }
  }
  for (auto& r : mesh.faces_) std::fill(std::begin(r.twin), std::end(r.twin), kInvalidIndex);
  for (const auto& [key, h] : halfedge_of) {
    const auto from = static_cast<std::uint32_t>(key >> 32);
    const auto to = static_cast<std::uint32_t>(key & 0xffffffffu);
    const auto it = halfedge_of.find(edge_key(to, from));
    if (it != halfedge_of.end()) mesh.faces_[h / 3].twin[h % 3] = it->second;
  }
  mesh.n_live_faces_ = triangles.size();
  mesh.n_live_vertices_ = nv;

  for (std::uint32_t v = 0; v < nv; ++v) {
    if (mesh.vertex_face_[v] == kInvalidIndex) {
      throw std::invalid_argument("base mesh: vertex " + std::to_string(v) +
                                  " is used by no triangle");
    }
  }
  for (std::uint32_t f = 0; f < triangles.size(); ++f) {
    if (!mesh.is_paired(Face(f))) {
      throw std::invalid_argument("base mesh: the refinement edge of triangle " +
                                  std::to_string(f) +
                                  " is not its neighbour's refinement edge (not a "
                                  "triangulated quadrangulation)");
    }
  }
  // Vertex manifoldness: the fan reached by rotation must hold every corner of the vertex.
  std::vector<int> corners(nv, 0);
  for (const auto& t : triangles)
    for (std::uint32_t v : t) ++corners[v];
  for (std::uint32_t v = 0; v < nv; ++v) {
    int fan = 0;
    mesh.for_each_corner_around(Vertex(v), [&](Corner) { ++fan; });
    if (fan != corners[v]) {
      throw std::invalid_argument("base mesh: vertex " + std::to_string(v) +
                                  " is non-manifold (its triangles form more than one fan)");
    }
  }
  return mesh;
}

// --- traversal ---------------------------------------------------------------------------

bool Mesh48::is_boundary(Vertex v) const {
  const Corner first = first_corner_ccw(v);
  return faces_[first.face.idx].twin[next(next(first.local))] == kInvalidIndex;
}

int Mesh48::valence(Vertex v) const {
  int faces = 0;
  for_each_corner_around(v, [&](Corner) { ++faces; });
  return is_boundary(v) ? faces + 1 : faces;
}

void Mesh48::one_ring(Vertex v, std::vector<Vertex>& ring) const {
  ring.clear();
  Corner last{};
  for_each_corner_around(v, [&](Corner c) {
    ring.push_back(vertex(c.face, next(c.local)));
    last = c;
  });
  if (is_boundary(v)) ring.push_back(vertex(last.face, prev(last.local)));
}

void Mesh48::incident_faces(Vertex v, std::vector<Face>& faces) const {
  faces.clear();
  for_each_corner_around(v, [&](Corner c) { faces.push_back(c.face); });
}

std::vector<Vertex> Mesh48::live_vertices() const {
  std::vector<Vertex> out;
  out.reserve(n_live_vertices_);
  for (std::uint32_t v = 0; v < vertex_face_.size(); ++v)
    if (vertex_face_[v] != kInvalidIndex) out.emplace_back(v);
  return out;
}

std::vector<Face> Mesh48::live_faces() const {
  std::vector<Face> out;
  out.reserve(n_live_faces_);
  for (std::uint32_t f = 0; f < faces_.size(); ++f)
    if (faces_[f].v[0] != kInvalidIndex) out.emplace_back(f);
  return out;
}

// --- listeners ---------------------------------------------------------------------------

void Mesh48::add_listener(MeshListener* listener) {
  listeners_.push_back(listener);
}

void Mesh48::remove_listener(MeshListener* listener) {
  listeners_.erase(std::remove(listeners_.begin(), listeners_.end(), listener), listeners_.end());
}

void Mesh48::notify_split(const DiamondChange& change) {
  for (MeshListener* l : listeners_) l->after_split(*this, change);
}

void Mesh48::notify_weld(const DiamondChange& change) {
  for (MeshListener* l : listeners_) l->after_weld(*this, change);
}

// --- split -------------------------------------------------------------------------------

Vertex Mesh48::split(Face f) {
  // The neighbours a split forces are coarser than f, so checking f bounds them all.
  if (faces_[f.idx].depth >= kMaxDepth) return Vertex();
  // A 4-8 mesh keeps the face across a refinement edge at most one bisection coarser, so one
  // forced split of the neighbour (recursively conforming itself) pairs the edge.
  const std::uint32_t t = faces_[f.idx].twin[0];
  if (t != kInvalidIndex && t % 3 != 0) {
    split(Face(t / 3));
    if (!is_paired(f)) throw std::logic_error("Mesh48::split: mesh is not a 4-8 mesh");
  }
  return split_diamond(f);
}

// Replaces the parent face (apex, a, b) of `half` by its two children around m (see
// Bisection); the links across the refinement edge are made by the caller.
void Mesh48::bisect_half(Bisection& half, std::uint32_t m) {
  const std::uint32_t p = half.parent.idx;
  const FaceRecord old = faces_[p];
  const std::uint32_t c1 = allocate_face();
  const auto depth = static_cast<std::uint8_t>(old.depth + 1);
  set_face(p, m, old.v[0], old.v[1], depth);   // (m, apex, a)
  set_face(c1, m, old.v[2], old.v[0], depth);  // (m, b, apex)
  // apex and a are still in slot p; b left it.
  if (vertex_face_[old.v[2]] == p) vertex_face_[old.v[2]] = c1;
  link(p, 0, old.twin[2]);
  link(c1, 0, old.twin[1]);
  link(p, 2, 3 * c1 + 1);
  half.children = {Face(p), Face(c1)};
  half.parent_vertices = {Vertex(old.v[0]), Vertex(old.v[1]), Vertex(old.v[2])};
}

Vertex Mesh48::split_diamond(Face f) {
  const FaceRecord& rec = faces_[f.idx];
  const std::uint32_t a = rec.v[1], b = rec.v[2];
  const std::uint32_t twin0 = rec.twin[0];
  const std::uint8_t depth = rec.depth;
  const std::uint32_t m = allocate_vertex();
  positions_[m] = 0.5 * (positions_[a] + positions_[b]);
  if (has_uvs_) uvs_[m] = 0.5 * (uvs_[a] + uvs_[b]);
  lineage_[m] = {a, b, static_cast<std::uint8_t>(depth + 1)};
  vertex_face_[m] = f.idx;

  DiamondChange change;
  change.vertex = Vertex(m);
  change.parents = {Vertex(a), Vertex(b)};
  change.count = twin0 == kInvalidIndex ? 1 : 2;
  change.halves[0].parent = f;
  bisect_half(change.halves[0], m);
  if (change.count == 2) {
    change.halves[1].parent = Face(twin0 / 3);
    bisect_half(change.halves[1], m);
    // f's children meet the neighbour's across the two halves of the old edge:
    // (a -> m) pairs with (m -> a), (m -> b) with (b -> m).
    const Bisection& hf = change.halves[0];
    const Bisection& hg = change.halves[1];
    link(hf.children[0].idx, 1, 3 * hg.children[1].idx + 2);
    link(hf.children[1].idx, 2, 3 * hg.children[0].idx + 1);
  } else {
    faces_[change.halves[0].children[0].idx].twin[1] = kInvalidIndex;
    faces_[change.halves[0].children[1].idx].twin[2] = kInvalidIndex;
  }
  notify_split(change);
  return Vertex(m);
}

// --- weld --------------------------------------------------------------------------------

// Collects the faces around v counter-clockwise (starting at the boundary for a boundary
// vertex) while they are at most four and all have v as their newest vertex; returns their
// number, or 0 when v is not the centre of such a star.
int Mesh48::collect_weld_star(Vertex v, std::array<Corner, 4>& star) const {
  const Corner start = corner(v);
  if (start.local != 0) return 0;
  star[0] = start;
  int count = 1;
  for (Corner c = rotate_ccw(start); c.face != start.face; c = rotate_ccw(c)) {
    if (!c.face.is_valid()) {
      // Open fan: the faces clockwise of the start come first.
      for (Corner b = rotate_cw(start); b.face.is_valid(); b = rotate_cw(b)) {
        if (count == 4 || b.local != 0) return 0;
        std::copy_backward(star.begin(), star.begin() + count, star.begin() + count + 1);
        star[0] = b;
        ++count;
      }
      return count == 2 ? 2 : 0;
    }
    if (count == 4 || c.local != 0) return 0;
    star[count++] = c;
  }
  return count == 4 ? 4 : 0;
}

bool Mesh48::can_weld(Vertex v) const {
  DiamondChange change;
  return plan_weld(v, change);
}

bool Mesh48::weld(Vertex v) {
  DiamondChange change;
  if (!plan_weld(v, change)) return false;
  apply_weld(change);
  return true;
}

// The star holds the faces around v counter-clockwise, (v, n_i, n_i+1). The children of one
// parent face share a non-parent ring vertex: (m, apex, a) follows (m, b, apex).
bool Mesh48::plan_weld(Vertex v, DiamondChange& change) const {
  if (v.idx >= vertex_face_.size() || !is_alive(v) || is_base(v)) return false;
  std::array<Corner, 4> star;
  const int count = collect_weld_star(v, star);
  if (count == 0) return false;
  const std::uint32_t pa = lineage_[v.idx].parent_a, pb = lineage_[v.idx].parent_b;
  auto ring = [&](int i) { return faces_[star[(i + count) % count].face.idx].v[1]; };
  change.vertex = v;
  change.parents = {Vertex(pa), Vertex(pb)};
  change.count = count / 2;
  if (count == 2) {
    // Boundary: star = [(m, b, apex), (m, apex, a)].
    if (faces_[star[1].face.idx].v[2] != pa || ring(0) != pb) return false;
    change.halves[0].children = {star[1].face, star[0].face};
  } else {
    int j = 0;
    while (j < 4 && ring(j) != pa) ++j;
    if (j == 4 || ring(j + 2) != pb) return false;
    change.halves[0].children = {star[(j + 3) % 4].face, star[(j + 2) % 4].face};
    change.halves[1].children = {star[(j + 1) % 4].face, star[j].face};
  }
  for (int h = 0; h < change.count; ++h) {
    Bisection& half = change.halves[h];
    const FaceRecord& c0 = faces_[half.children[0].idx];  // (m, apex, x)
    const FaceRecord& c1 = faces_[half.children[1].idx];  // (m, y, apex)
    half.parent = half.children[0];
    half.parent_vertices = {Vertex(c0.v[1]), Vertex(c0.v[2]), Vertex(c1.v[1])};
  }
  return true;
}

void Mesh48::apply_weld(const DiamondChange& change) {
  for (int h = 0; h < change.count; ++h) {
    const Bisection& half = change.halves[h];
    const FaceRecord c0 = faces_[half.children[0].idx];
    const FaceRecord c1 = faces_[half.children[1].idx];
    const std::uint32_t p = half.parent.idx;
    const auto& pv = half.parent_vertices;
    set_face(p, pv[0].idx, pv[1].idx, pv[2].idx, static_cast<std::uint8_t>(c0.depth - 1));
    // apex and x stay in slot p; apex and y leave the freed child.
    const std::uint32_t freed = half.children[1].idx;
    if (vertex_face_[pv[0].idx] == freed) vertex_face_[pv[0].idx] = p;
    if (vertex_face_[pv[2].idx] == freed) vertex_face_[pv[2].idx] = p;
    faces_[p].twin[0] = kInvalidIndex;
    link(p, 1, c1.twin[0]);
    link(p, 2, c0.twin[0]);
    faces_[half.children[1].idx].v[0] = kInvalidIndex;
    free_faces_.push_back(half.children[1].idx);
    --n_live_faces_;
  }
  if (change.count == 2) link(change.halves[0].parent.idx, 0, 3 * change.halves[1].parent.idx);
  const std::uint32_t v = change.vertex.idx;
  vertex_face_[v] = kInvalidIndex;
  lineage_[v] = Lineage{};
  free_vertices_.push_back(v);
  --n_live_vertices_;
  notify_weld(change);
}

}  // namespace dynamesh
