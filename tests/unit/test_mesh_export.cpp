// Export tests: files written by dynamesh are read back by readers that share no code with
// the writer (tinyobjloader for OBJ; a small PLY reader written from the format spec,
// ply_reader.h).
#include <gtest/gtest.h>
#include <tiny_obj_loader.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/adapt/mesh_snapshot.h"
#include "core/io/mesh_export.h"
#include "core/mesh/base_meshes.h"
#include "ply_reader.h"

namespace dynamesh {
namespace {

namespace fs = std::filesystem;
using test::PlyData;
using test::read_ply;

MeshSnapshot sample_snapshot() {
  Mesh48 mesh = make_grid_mesh(3, 2, Vec2(-1, -1), Vec2(1, 1));
  for (int i = 0; i < 5; ++i) mesh.split(mesh.live_faces()[static_cast<std::size_t>(i * 3)]);
  mesh.weld(Vertex(static_cast<std::uint32_t>(mesh.vertex_capacity() - 1)));  // leave a hole in ids
  for (Vertex v : mesh.live_vertices()) {
    Vec3& p = mesh.position(v);
    p.y() = 0.25 * p.x() * p.z();
  }
  ScalarField height{"height", std::vector<float>(mesh.vertex_capacity(), 0.0f)};
  for (Vertex v : mesh.live_vertices())
    height.values[v.idx] = static_cast<float>(mesh.position(v).y());
  return make_snapshot(mesh, nullptr, {height});
}

std::string temp_path(const std::string& name) {
  return (fs::temp_directory_path() / ("dynamesh_test_" + name)).string();
}

void expect_same_mesh(const MeshSnapshot& snap, const PlyData& ply) {
  ASSERT_EQ(ply.vertices.size(), snap.n_vertices());
  ASSERT_EQ(ply.faces.size(), snap.n_triangles());
  ASSERT_EQ(ply.vertex_properties.size(), 7u);
  EXPECT_EQ(ply.vertex_properties[6], "height");
  for (std::size_t v = 0; v < snap.n_vertices(); ++v) {
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(ply.vertices[v][a], snap.positions[3 * v + a], 1e-6);
    EXPECT_NEAR(ply.vertices[v][6], ply.vertices[v][1], 1e-6);  // height field == y
  }
  for (std::size_t f = 0; f < snap.n_triangles(); ++f) {
    ASSERT_EQ(ply.faces[f].size(), 3u);
    for (int a = 0; a < 3; ++a) EXPECT_EQ(ply.faces[f][a], snap.triangles[3 * f + a]);
  }
}

TEST(MeshExport, BinaryAndAsciiPlyReadBackIndependently) {
  const MeshSnapshot snap = sample_snapshot();
  for (PlyFormat format : {PlyFormat::kBinary, PlyFormat::kAscii}) {
    const std::string path = temp_path(format == PlyFormat::kBinary ? "b.ply" : "a.ply");
    write_ply(path, snap, format);
    expect_same_mesh(snap, read_ply(path));
    EXPECT_FALSE(fs::exists(path + ".partial"));
    fs::remove(path);
  }
}

TEST(MeshExport, ObjReadBackByTinyObjLoader) {
  const MeshSnapshot snap = sample_snapshot();
  const std::string path = temp_path("m.obj");
  write_obj(path, snap);
  tinyobj::ObjReader reader;
  ASSERT_TRUE(reader.ParseFromFile(path)) << reader.Error();
  const auto& attrib = reader.GetAttrib();
  ASSERT_EQ(attrib.vertices.size(), snap.positions.size());
  for (std::size_t i = 0; i < snap.positions.size(); ++i)
    EXPECT_NEAR(attrib.vertices[i], snap.positions[i], 1e-6);
  ASSERT_EQ(reader.GetShapes().size(), 1u);
  const auto& indices = reader.GetShapes()[0].mesh.indices;
  ASSERT_EQ(indices.size(), snap.triangles.size());
  for (std::size_t i = 0; i < indices.size(); ++i) {
    EXPECT_EQ(static_cast<std::uint32_t>(indices[i].vertex_index), snap.triangles[i]);
    // The first scalar field rides in the texture coordinate.
    EXPECT_NEAR(attrib.texcoords[2 * indices[i].texcoord_index],
                snap.fields[0].values[snap.triangles[i]], 1e-6);
  }
  fs::remove(path);
}

TEST(MeshExport, UnwritablePathThrowsAndLeavesNothing) {
  const MeshSnapshot snap = sample_snapshot();
  EXPECT_THROW(write_ply("/nonexistent-dir/x.ply", snap), std::runtime_error);
  EXPECT_THROW(write_mesh(temp_path("x.stl"), snap), std::invalid_argument);
  EXPECT_FALSE(fs::exists(temp_path("x.stl")));
}

TEST(MeshExport, SnapshotRenumbersLiveVerticesCompactly) {
  const MeshSnapshot snap = sample_snapshot();
  std::vector<int> used(snap.n_vertices(), 0);
  for (std::uint32_t i : snap.triangles) {
    ASSERT_LT(i, snap.n_vertices());
    used[i] = 1;
  }
  for (int u : used) EXPECT_EQ(u, 1);
  for (std::size_t v = 0; v < snap.n_vertices(); ++v) {
    const Vec3 n(snap.normals[3 * v], snap.normals[3 * v + 1], snap.normals[3 * v + 2]);
    EXPECT_NEAR(n.norm(), 1.0, 1e-6);
  }
}

}  // namespace
}  // namespace dynamesh
