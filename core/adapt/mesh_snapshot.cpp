// make_snapshot: compaction of the live mesh into the read-only view.
#include "core/adapt/mesh_snapshot.h"

namespace dynamesh {

const ScalarField* MeshSnapshot::field(const std::string& name) const {
  for (const ScalarField& f : fields)
    if (f.name == name) return &f;
  return nullptr;
}

MeshSnapshot make_snapshot(const Mesh48& mesh, const std::vector<Vec3>* vertex_normals,
                           const std::vector<ScalarField>& vertex_fields) {
  MeshSnapshot snap;
  std::vector<std::uint32_t> compact(mesh.vertex_capacity(), kInvalidIndex);
  const std::vector<Vertex> vertices = mesh.live_vertices();
  snap.positions.reserve(3 * vertices.size());
  for (std::uint32_t i = 0; i < vertices.size(); ++i) {
    compact[vertices[i].idx] = i;
    const Vec3& p = mesh.position(vertices[i]);
    snap.bounds.extend(p);
    for (int a = 0; a < 3; ++a) snap.positions.push_back(static_cast<float>(p[a]));
  }
  std::vector<Vec3> normals(vertices.size(), Vec3::Zero());
  snap.triangles.reserve(3 * mesh.n_faces());
  for (Face f : mesh.live_faces()) {
    const auto vs = mesh.vertices(f);
    for (Vertex v : vs) snap.triangles.push_back(compact[v.idx]);
    if (vertex_normals) continue;
    // Area-weighted: the cross product's length is twice the area.
    const Vec3 n = (mesh.position(vs[1]) - mesh.position(vs[0]))
                       .cross(mesh.position(vs[2]) - mesh.position(vs[0]));
    for (Vertex v : vs) normals[compact[v.idx]] += n;
  }
  snap.normals.reserve(3 * vertices.size());
  for (std::uint32_t i = 0; i < vertices.size(); ++i) {
    Vec3 n = vertex_normals ? (*vertex_normals)[vertices[i].idx] : normals[i];
    const double len = n.norm();
    n = len > 0 ? Vec3(n / len) : Vec3::UnitZ();
    for (int a = 0; a < 3; ++a) snap.normals.push_back(static_cast<float>(n[a]));
  }
  for (const ScalarField& field : vertex_fields) {
    ScalarField out{field.name, {}};
    out.values.reserve(vertices.size());
    for (Vertex v : vertices) out.values.push_back(field.values[v.idx]);
    snap.fields.push_back(std::move(out));
  }
  return snap;
}

}  // namespace dynamesh
