// A small PLY reader written from the format spec, sharing no code with the writer
// (core/io/mesh_export): for tests that read back what dynamesh wrote.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/geometry/vector_types.h"

namespace dynamesh::test {

struct PlyData {
  std::vector<std::string> vertex_properties;
  std::vector<std::vector<double>> vertices;  // one row of properties per vertex
  std::vector<std::vector<std::uint32_t>> faces;
};

// Reads the subset of PLY that the writer claims to produce: float vertex properties and a
// uchar/uint face list, ASCII or binary little-endian.
inline PlyData read_ply(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string line, format;
  std::size_t n_vertices = 0, n_faces = 0;
  PlyData ply;
  std::getline(in, line);
  EXPECT_EQ(line, "ply");
  std::string element;
  while (std::getline(in, line) && line != "end_header") {
    std::istringstream words(line);
    std::string word;
    words >> word;
    if (word == "format") words >> format;
    if (word == "element") {
      words >> element;
      (element == "vertex" ? n_vertices : n_faces) = std::stoul(line.substr(line.rfind(' ') + 1));
    }
    if (word == "property" && element == "vertex") {
      std::string type, name;
      words >> type >> name;
      EXPECT_EQ(type, "float");
      ply.vertex_properties.push_back(name);
    }
  }
  const bool binary = format == "binary_little_endian";
  const std::size_t k = ply.vertex_properties.size();
  for (std::size_t v = 0; v < n_vertices; ++v) {
    std::vector<double> row(k);
    for (std::size_t i = 0; i < k; ++i) {
      if (binary) {
        float x;
        in.read(reinterpret_cast<char*>(&x), 4);
        row[i] = x;
      } else {
        in >> row[i];
      }
    }
    ply.vertices.push_back(row);
  }
  for (std::size_t f = 0; f < n_faces; ++f) {
    std::vector<std::uint32_t> face;
    unsigned count = 0;
    if (binary) {
      unsigned char c;
      in.read(reinterpret_cast<char*>(&c), 1);
      count = c;
    } else {
      in >> count;
    }
    for (unsigned i = 0; i < count; ++i) {
      std::uint32_t idx;
      if (binary)
        in.read(reinterpret_cast<char*>(&idx), 4);
      else
        in >> idx;
      face.push_back(idx);
    }
    ply.faces.push_back(face);
  }
  EXPECT_TRUE(static_cast<bool>(in)) << "file ended early";
  return ply;
}

struct PlyMeasure {
  double area = 0.0, volume = 0.0;
};

// Area and enclosed volume (divergence theorem) of a closed mesh read back from PLY, in one
// pass; with `stretch`, of that mesh scaled by it along the world's axes (voxel-size tests
// compare layers of volumes whose voxels differ by such a stretch).
inline PlyMeasure measure_ply(const PlyData& ply, const Vec3& stretch = Vec3::Ones()) {
  PlyMeasure m;
  for (const auto& f : ply.faces) {
    Vec3 p[3];
    for (int i = 0; i < 3; ++i)
      p[i] = stretch.cwiseProduct(
          Vec3(ply.vertices[f[i]][0], ply.vertices[f[i]][1], ply.vertices[f[i]][2]));
    m.area += 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
    m.volume += p[0].dot(p[1].cross(p[2])) / 6.0;
  }
  return m;
}

// The column of a vertex property (fails the test, returns -1, when absent).
inline int ply_column(const PlyData& ply, const std::string& name) {
  for (std::size_t i = 0; i < ply.vertex_properties.size(); ++i)
    if (ply.vertex_properties[i] == name) return static_cast<int>(i);
  ADD_FAILURE() << "no vertex property '" << name << "'";
  return -1;
}

}  // namespace dynamesh::test
