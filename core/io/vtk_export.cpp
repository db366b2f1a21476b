#include "core/io/vtk_export.h"

#include <ostream>

#include "core/io/atomic_file.h"

namespace dynamesh {
namespace {

template <class T>
void write_values(std::ostream& out, const std::vector<T>& values) {
  for (std::size_t i = 0; i < values.size(); ++i) out << (i % 12 == 0 ? "\n" : " ") << values[i];
  out << "\n";
}

}  // namespace

void write_vtp(const std::string& path, const MeshSnapshot& mesh) {
  AtomicFile file(path);
  std::ostream& out = file.stream();
  out.precision(9);
  out << "<?xml version=\"1.0\"?>\n"
         "<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n<PolyData>\n"
      << "<Piece NumberOfPoints=\"" << mesh.n_vertices() << "\" NumberOfPolys=\""
      << mesh.n_triangles() << "\">\n<PointData";
  if (!mesh.fields.empty()) out << " Scalars=\"" << mesh.fields.front().name << "\"";
  if (mesh.normals.size() == mesh.positions.size()) out << " Normals=\"normals\"";
  out << ">\n";
  for (const ScalarField& f : mesh.fields) {
    out << "<DataArray type=\"Float32\" Name=\"" << f.name << "\" format=\"ascii\">";
    write_values(out, f.values);
    out << "</DataArray>\n";
  }
  if (mesh.normals.size() == mesh.positions.size()) {
    out << "<DataArray type=\"Float32\" Name=\"normals\" NumberOfComponents=\"3\" "
           "format=\"ascii\">";
    write_values(out, mesh.normals);
    out << "</DataArray>\n";
  }
  out << "</PointData>\n<Points>\n"
         "<DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">";
  write_values(out, mesh.positions);
  out << "</DataArray>\n</Points>\n<Polys>\n"
         "<DataArray type=\"UInt32\" Name=\"connectivity\" format=\"ascii\">";
  write_values(out, mesh.triangles);
  out << "</DataArray>\n<DataArray type=\"UInt32\" Name=\"offsets\" format=\"ascii\">";
  std::vector<std::uint64_t> offsets(mesh.n_triangles());
  for (std::size_t i = 0; i < offsets.size(); ++i) offsets[i] = 3 * (i + 1);
  write_values(out, offsets);
  out << "</DataArray>\n</Polys>\n</Piece>\n</PolyData>\n</VTKFile>\n";
  file.commit();
}

void write_pvd(const std::string& path, const std::vector<std::pair<double, std::string>>& frames) {
  AtomicFile file(path);
  std::ostream& out = file.stream();
  out.precision(10);
  out << "<?xml version=\"1.0\"?>\n"
         "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
         "<Collection>\n";
  for (const auto& [time, name] : frames)
    out << "  <DataSet timestep=\"" << time << "\" group=\"\" part=\"0\" file=\"" << name
        << "\"/>\n";
  out << "</Collection>\n</VTKFile>\n";
  file.commit();
}

}  // namespace dynamesh
