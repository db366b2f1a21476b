#include "core/io/mesh_export.h"

#include <bit>
#include <cstdint>
#include <stdexcept>

#include "core/io/atomic_file.h"

namespace dynamesh {
namespace {

static_assert(std::endian::native == std::endian::little,
              "binary PLY export assumes a little-endian host");

void write_ply_header(std::ostream& out, const MeshSnapshot& mesh, PlyFormat format) {
  out << "ply\nformat " << (format == PlyFormat::kBinary ? "binary_little_endian" : "ascii")
      << " 1.0\ncomment dynamesh adapted mesh, t = " << mesh.time << "\nelement vertex "
      << mesh.n_vertices() << "\nproperty float x\nproperty float y\nproperty float z\n"
      << "property float nx\nproperty float ny\nproperty float nz\n";
  for (const ScalarField& f : mesh.fields) out << "property float " << f.name << "\n";
  out << "element face " << mesh.n_triangles() << "\nproperty list uchar uint vertex_indices\n"
      << "end_header\n";
}

template <class T>
void put(std::ostream& out, T value) {
  out.write(reinterpret_cast<const char*>(&value), sizeof(T));
}

void write_ply_body(std::ostream& out, const MeshSnapshot& mesh, PlyFormat format) {
  const bool binary = format == PlyFormat::kBinary;
  if (!binary) out.precision(9);
  for (std::size_t v = 0; v < mesh.n_vertices(); ++v) {
    auto emit = [&](float x, bool last) {
      if (binary)
        put(out, x);
      else
        out << x << (last ? '\n' : ' ');
    };
    for (int a = 0; a < 3; ++a) emit(mesh.positions[3 * v + a], false);
    for (int a = 0; a < 3; ++a) emit(mesh.normals[3 * v + a], mesh.fields.empty() && a == 2);
    for (std::size_t k = 0; k < mesh.fields.size(); ++k)
      emit(mesh.fields[k].values[v], k + 1 == mesh.fields.size());
  }
  for (std::size_t t = 0; t < mesh.n_triangles(); ++t) {
    if (binary) {
      put<std::uint8_t>(out, 3);
      for (int a = 0; a < 3; ++a) put<std::uint32_t>(out, mesh.triangles[3 * t + a]);
    } else {
      out << "3 " << mesh.triangles[3 * t] << ' ' << mesh.triangles[3 * t + 1] << ' '
          << mesh.triangles[3 * t + 2] << '\n';
    }
  }
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

void write_ply(const std::string& path, const MeshSnapshot& mesh, PlyFormat format) {
  AtomicFile file(path, format == PlyFormat::kBinary ? std::ios::binary : std::ios::out);
  write_ply_header(file.stream(), mesh, format);
  write_ply_body(file.stream(), mesh, format);
  file.commit();
}

void write_obj(const std::string& path, const MeshSnapshot& mesh) {
  AtomicFile file(path);
  std::ostream& out = file.stream();
  out.precision(9);
  out << "# dynamesh adapted mesh, t = " << mesh.time << "\n";
  for (const ScalarField& f : mesh.fields) out << "# vertex field: " << f.name << "\n";
  if (!mesh.fields.empty()) out << "# vt holds the field '" << mesh.fields[0].name << "'\n";
  for (std::size_t v = 0; v < mesh.n_vertices(); ++v) {
    out << "v " << mesh.positions[3 * v] << ' ' << mesh.positions[3 * v + 1] << ' '
        << mesh.positions[3 * v + 2] << '\n';
    out << "vn " << mesh.normals[3 * v] << ' ' << mesh.normals[3 * v + 1] << ' '
        << mesh.normals[3 * v + 2] << '\n';
    if (!mesh.fields.empty()) out << "vt " << mesh.fields[0].values[v] << '\n';
  }
  const bool uv = !mesh.fields.empty();
  for (std::size_t t = 0; t < mesh.n_triangles(); ++t) {
    out << 'f';
    for (int a = 0; a < 3; ++a) {
      const std::uint32_t i = mesh.triangles[3 * t + a] + 1;
      out << ' ' << i << '/' << (uv ? std::to_string(i) : std::string()) << '/' << i;
    }
    out << '\n';
  }
  file.commit();
}

void write_mesh(const std::string& path, const MeshSnapshot& mesh) {
  if (ends_with(path, ".ply")) return write_ply(path, mesh, PlyFormat::kBinary);
  if (ends_with(path, ".obj")) return write_obj(path, mesh);
  throw std::invalid_argument("cannot export " + path + ": use a .ply or .obj file name");
}

}  // namespace dynamesh
