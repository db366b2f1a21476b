// Mesh48::check(): the full invariant checker. It trusts none of the mesh's own shortcuts
// (traversals are bounded, counts are recomputed) so that it can report a corrupted mesh
// instead of looping or crashing on it.
#include <sstream>
#include <unordered_set>

#include "core/mesh/mesh48.h"

namespace dynamesh {
namespace {

class Problems {
 public:
  explicit Problems(CheckReport& report) : report_(report) {}
  template <class... Args>
  void add(const Args&... args) {
    if (report_.problems.size() >= kMaxProblems) return;
    std::ostringstream out;
    (out << ... << args);
    report_.problems.push_back(out.str());
  }

 private:
  static constexpr std::size_t kMaxProblems = 64;
  CheckReport& report_;
};

}  // namespace

CheckReport Mesh48::check() const {
  CheckReport report;
  Problems problem(report);
  const std::size_t nv = vertex_face_.size();
  std::vector<int> corner_count(nv, 0);
  std::unordered_set<std::uint64_t> directed;
  directed.reserve(3 * n_live_faces_);

  // Faces: valid distinct live vertices; symmetric twins joining the same two vertices in
  // opposite directions (conforming, consistently oriented); each directed edge used once
  // (edge-manifold); 4-8 structure across the refinement edge.
  std::size_t live_faces = 0;
  for (std::uint32_t f = 0; f < faces_.size(); ++f) {
    const FaceRecord& r = faces_[f];
    if (r.v[0] == kInvalidIndex) continue;
    ++live_faces;
    bool vertices_ok = true;
    for (int i = 0; i < 3; ++i) {
      if (r.v[i] >= nv || vertex_face_[r.v[i]] == kInvalidIndex) {
        problem.add("face ", f, " uses dead or unknown vertex ", r.v[i]);
        vertices_ok = false;
      }
    }
    if (!vertices_ok) continue;
    if (r.v[0] == r.v[1] || r.v[1] == r.v[2] || r.v[0] == r.v[2])
      problem.add("face ", f, " repeats a vertex");
    for (int i = 0; i < 3; ++i) {
      ++corner_count[r.v[i]];
      const std::uint32_t from = r.v[(i + 1) % 3], to = r.v[(i + 2) % 3];
      if (!directed.insert((std::uint64_t{from} << 32) | to).second)
        problem.add("directed edge (", from, ", ", to,
                    ") appears twice: non-manifold or "
                    "inconsistent orientation");
      const std::uint32_t t = r.twin[i];
      if (t == kInvalidIndex) continue;
      if (t / 3 >= faces_.size() || faces_[t / 3].v[0] == kInvalidIndex) {
        problem.add("face ", f, " edge ", i, " links to dead face ", t / 3);
        continue;
      }
      const FaceRecord& n = faces_[t / 3];
      if (n.twin[t % 3] != 3 * f + i) problem.add("face ", f, " edge ", i, " link not symmetric");
      if (n.v[(t % 3 + 1) % 3] != to || n.v[(t % 3 + 2) % 3] != from)
        problem.add("face ", f, " edge ", i, " and its twin join different vertices");
    }
    const std::uint32_t t0 = r.twin[0];
    if (t0 != kInvalidIndex && t0 / 3 < faces_.size()) {
      const int nd = faces_[t0 / 3].depth;
      const bool paired = t0 % 3 == 0 && nd == r.depth;
      const bool coarser = t0 % 3 != 0 && nd + 1 == r.depth;
      if (!paired && !coarser)
        problem.add("face ", f, " (depth ", int{r.depth}, "): the face across its refinement edge ",
                    "is neither its pair nor one bisection coarser (depth ", nd, ")");
    }
  }
  if (live_faces != n_live_faces_)
    problem.add("live face count ", n_live_faces_, " but ", live_faces, " faces are alive");
  if (faces_.size() - live_faces != free_faces_.size())
    problem.add("free face list holds ", free_faces_.size(), ", expected ",
                faces_.size() - live_faces);
  // A boundary halfedge whose reverse exists elsewhere is a missing link (a T-junction or a
  // crack between faces that should be neighbours).
  for (std::uint32_t f = 0; f < faces_.size(); ++f) {
    const FaceRecord& r = faces_[f];
    if (r.v[0] == kInvalidIndex) continue;
    for (int i = 0; i < 3; ++i) {
      if (r.twin[i] != kInvalidIndex) continue;
      const std::uint32_t from = r.v[(i + 1) % 3], to = r.v[(i + 2) % 3];
      if (directed.count((std::uint64_t{to} << 32) | from))
        problem.add("boundary edge (", from, ", ", to, ") of face ", f,
                    " has an unlinked reverse: the mesh is not conforming");
    }
  }
  if (!report.ok()) return report;  // vertex checks below traverse links checked above

  std::size_t live_vertices = 0;
  for (std::uint32_t v = 0; v < nv; ++v) {
    if (vertex_face_[v] == kInvalidIndex) {
      if (corner_count[v] != 0) problem.add("dead vertex ", v, " is used by a face");
      continue;
    }
    ++live_vertices;
    const Vertex vh(v);
    if (vertex_face_[v] >= faces_.size() || faces_[vertex_face_[v]].v[0] == kInvalidIndex) {
      problem.add("vertex ", v, " points at a dead or unknown face");
      continue;
    }
    const Corner c = corner(vh);
    if (c.face.idx >= faces_.size() || c.local < 0 || faces_[c.face.idx].v[c.local] != v) {
      problem.add("vertex ", v, " points at a face that does not hold it");
      continue;
    }
    // The fan reached by rotation must hold every corner of the vertex (vertex-manifold).
    int fan = 0;
    Corner first = c;
    for (int guard = 0; guard <= corner_count[v]; ++guard) {
      const Corner p = rotate_cw(first);
      if (!p.face.is_valid() || p.face == c.face) break;
      first = p;
    }
    Corner it = first;
    do {
      ++fan;
      it = rotate_ccw(it);
    } while (it.face.is_valid() && it.face != first.face && fan <= corner_count[v]);
    if (fan != corner_count[v]) {
      problem.add("vertex ", v, " is non-manifold: its fan has ", fan, " of its ", corner_count[v],
                  " faces");
      continue;
    }
    if (is_base(vh)) continue;
    const auto [pa, pb] = parents(vh);
    if (pa.idx >= nv || pb.idx >= nv || !is_alive(pa) || !is_alive(pb)) {
      problem.add("vertex ", v, " has a dead parent");
      continue;
    }
    if (level(pa) >= level(vh) || level(pb) >= level(vh))
      problem.add("vertex ", v, " (level ", level(vh), ") is not finer than its parents");
    const bool boundary = is_boundary(vh);
    const int val = valence(vh);
    if (boundary ? (val < 3 || val > 5) : (val < 4 || val > 8))
      problem.add("split-born vertex ", v, " has valence ", val, boundary ? " (boundary)" : "");
    if (!can_weld(vh)) continue;
    std::vector<Vertex> ring;
    one_ring(vh, ring);
    for (Vertex n : ring)
      if (level(n) >= level(vh))
        problem.add("weldable vertex ", v, " has neighbour ", n.idx, " of level ", level(n),
                    " >= its own ", level(vh));
    const std::size_t k = ring.size();
    bool opposite = false;
    for (std::size_t i = 0; i < k; ++i)
      opposite = opposite || (ring[i] == pa && ring[(i + (boundary ? 1 : 2)) % k] == pb);
    if (!opposite)
      problem.add("weldable vertex ", v, ": its parents ", pa.idx, ", ", pb.idx,
                  " are not the ends of its parent edge in its star");
  }
  if (live_vertices != n_live_vertices_)
    problem.add("live vertex count ", n_live_vertices_, " but ", live_vertices, " are alive");
  if (nv - live_vertices != free_vertices_.size())
    problem.add("free vertex list holds ", free_vertices_.size(), ", expected ",
                nv - live_vertices);
  return report;
}

}  // namespace dynamesh
