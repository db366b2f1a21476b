#include "core/surface/expression/triangle_mesh_file.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace dynamesh {

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw std::invalid_argument("base mesh " + path + ": " + what);
}

// Adds the polygon `corners` as a triangle fan, checking indices.
void add_polygon(const std::string& path, TriangleMesh& mesh,
                 const std::vector<std::int64_t>& corners, std::size_t vertex_count) {
  if (corners.size() < 3)
    fail(path, "a face has " + std::to_string(corners.size()) + " corners (at least 3 needed)");
  for (std::int64_t c : corners)
    if (c < 0 || static_cast<std::size_t>(c) >= vertex_count)
      fail(path,
           "a face refers to vertex " + std::to_string(c) + " of " + std::to_string(vertex_count));
  for (std::size_t k = 1; k + 1 < corners.size(); ++k)
    mesh.triangles.push_back({static_cast<std::uint32_t>(corners[0]),
                              static_cast<std::uint32_t>(corners[k]),
                              static_cast<std::uint32_t>(corners[k + 1])});
}

// One corner of an OBJ face, "i", "i/j", "i//k" or "i/j/k": the vertex index i, 1-based, or
// negative counting back from the last vertex read so far.
std::int64_t obj_corner(const std::string& path, std::size_t line_number, const std::string& word,
                        std::size_t vertex_count) {
  const std::string index = word.substr(0, word.find('/'));
  long long i = 0;
  const char* end = index.data() + index.size();
  const auto [ptr, ec] = std::from_chars(index.data(), end, i);
  if (ec != std::errc() || ptr != end || i == 0)
    fail(path, "line " + std::to_string(line_number) + ": bad face corner '" + word + "'");
  return i > 0 ? i - 1 : static_cast<std::int64_t>(vertex_count) + i;
}

// Wavefront OBJ, strictly: 'v' lines need three finite coordinates (a w or colour after them
// is ignored), 'f' lines at least three corners; other statements (vt, vn, g, o, s, usemtl,
// mtllib, l, ...) are ignored. A malformed or truncated line is an error naming its number.
TriangleMesh read_obj(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open the file");
  TriangleMesh mesh;
  std::string line;
  std::vector<std::int64_t> corners;
  for (std::size_t number = 1; std::getline(in, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword == "v") {
      Vec3 p;
      for (int a = 0; a < 3; ++a) {
        std::string word;
        words >> word;
        double x = 0;
        const char* end = word.data() + word.size();
        const auto [ptr, ec] = std::from_chars(word.data(), end, x);
        if (word.empty() || ec != std::errc() || ptr != end)
          fail(path, "line " + std::to_string(number) + ": a vertex needs three numbers, got '" +
                         line.substr(0, 80) + "'");
        p[a] = x;
      }
      mesh.positions.push_back(p);
    } else if (keyword == "f") {
      corners.clear();
      for (std::string word; words >> word;)
        corners.push_back(obj_corner(path, number, word, mesh.positions.size()));
      add_polygon(path, mesh, corners, mesh.positions.size());
    }
  }
  if (in.bad()) fail(path, "read error");
  return mesh;
}

// ---- PLY ----------------------------------------------------------------------------------

enum class PlyFormat { kAscii, kLittle, kBig };

int type_size(const std::string& type) {
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
  if (type == "int" || type == "uint" || type == "int32" || type == "uint32" || type == "float" ||
      type == "float32")
    return 4;
  if (type == "double" || type == "float64") return 8;
  return 0;
}

struct PlyProperty {
  std::string name, type;
  bool is_list = false;
  std::string count_type;
};

struct PlyElement {
  std::string name;
  std::size_t count = 0;
  std::vector<PlyProperty> properties;
};

class PlyValueReader {
 public:
  PlyValueReader(std::istream& in, PlyFormat format, const std::string& path)
      : in_(in), format_(format), path_(path) {}

  double read(const std::string& type) {
    if (format_ == PlyFormat::kAscii) {
      double x = 0;
      if (!(in_ >> x)) fail(path_, "ascii data ends early or holds a non-number");
      return x;
    }
    unsigned char bytes[8];
    const int n = type_size(type);
    if (!in_.read(reinterpret_cast<char*>(bytes), n)) fail(path_, "binary data ends early");
    if ((format_ == PlyFormat::kBig) != (std::endian::native == std::endian::big))
      std::reverse(bytes, bytes + n);
    auto as = [&](auto value) {
      std::memcpy(&value, bytes, sizeof value);
      return static_cast<double>(value);
    };
    if (type == "char" || type == "int8") return as(std::int8_t{});
    if (type == "uchar" || type == "uint8") return as(std::uint8_t{});
    if (type == "short" || type == "int16") return as(std::int16_t{});
    if (type == "ushort" || type == "uint16") return as(std::uint16_t{});
    if (type == "int" || type == "int32") return as(std::int32_t{});
    if (type == "uint" || type == "uint32") return as(std::uint32_t{});
    if (type == "float" || type == "float32") return as(float{});
    return as(double{});
  }

 private:
  std::istream& in_;
  PlyFormat format_;
  const std::string& path_;
};

TriangleMesh read_ply(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open the file");
  std::string line;
  if (!std::getline(in, line) || line.substr(0, 3) != "ply" ||
      line.find_first_not_of(" \r", 3) != std::string::npos)
    fail(path, "not a PLY file (the first line must be 'ply')");
  PlyFormat format = PlyFormat::kAscii;
  bool format_seen = false;
  std::vector<PlyElement> elements;
  for (;;) {
    if (!std::getline(in, line)) fail(path, "the header has no end_header line");
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword == "end_header") break;
    if (keyword == "comment" || keyword == "obj_info" || keyword.empty()) continue;
    if (keyword == "format") {
      std::string name, version;
      words >> name >> version;
      if (name == "ascii")
        format = PlyFormat::kAscii;
      else if (name == "binary_little_endian")
        format = PlyFormat::kLittle;
      else if (name == "binary_big_endian")
        format = PlyFormat::kBig;
      else
        fail(path, "unknown PLY format '" + name + "'");
      format_seen = true;
    } else if (keyword == "element") {
      PlyElement e;
      long long count = -1;
      words >> e.name >> count;
      if (e.name.empty() || count < 0) fail(path, "malformed header line '" + line + "'");
      e.count = static_cast<std::size_t>(count);
      elements.push_back(e);
    } else if (keyword == "property") {
      if (elements.empty()) fail(path, "a property comes before any element");
      PlyProperty p;
      words >> p.type;
      if (p.type == "list") {
        p.is_list = true;
        words >> p.count_type >> p.type;
        if (type_size(p.count_type) == 0) fail(path, "unknown list count type in '" + line + "'");
      }
      words >> p.name;
      if (type_size(p.type) == 0 || p.name.empty())
        fail(path, "malformed property line '" + line + "'");
      elements.back().properties.push_back(p);
    } else {
      fail(path, "unexpected header line '" + line + "'");
    }
  }
  if (!format_seen) fail(path, "the header has no format line");
  const std::uint64_t data_start = static_cast<std::uint64_t>(in.tellg());
  std::error_code ec;
  const std::uint64_t file_size = std::filesystem::file_size(path, ec);
  std::uint64_t room = ec || file_size < data_start ? 0 : file_size - data_start;
  // Each element's count is checked against the bytes left before anything is read: every
  // item takes at least its fixed-size properties and list counts (binary) or two characters
  // per value (ascii). A header claiming more is refused at once instead of read to the end.
  for (const PlyElement& e : elements) {
    if (e.properties.empty() && e.count > 0)
      fail(path,
           "element '" + e.name + "' has " + std::to_string(e.count) + " items but no properties");
    std::uint64_t item = 0;
    for (const PlyProperty& p : e.properties)
      item += format == PlyFormat::kAscii ? 2 : type_size(p.is_list ? p.count_type : p.type);
    if (e.count > room / std::max<std::uint64_t>(item, 1))
      fail(path, "element '" + e.name + "' claims " + std::to_string(e.count) +
                     " items, more than the file's remaining " + std::to_string(room) +
                     " bytes can hold (the data ends early)");
    room -= e.count * item;
  }

  TriangleMesh mesh;
  PlyValueReader reader(in, format, path);
  bool vertices_read = false;
  for (const PlyElement& e : elements) {
    const bool is_vertex = e.name == "vertex", is_face = e.name == "face";
    int xyz[3] = {-1, -1, -1};
    int face_list = -1;
    for (std::size_t k = 0; k < e.properties.size(); ++k) {
      const PlyProperty& p = e.properties[k];
      for (int a = 0; a < 3; ++a)
        if (is_vertex && !p.is_list && p.name == std::string(1, "xyz"[a]))
          xyz[a] = static_cast<int>(k);
      if (is_face && p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index"))
        face_list = static_cast<int>(k);
    }
    if (is_vertex && (xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0))
      fail(path, "the vertex element lacks an x, y or z property");
    if (is_face && face_list < 0) fail(path, "the face element lacks a vertex_indices list");
    if (is_face && !vertices_read) fail(path, "faces come before vertices");
    std::vector<std::int64_t> corners;
    for (std::size_t i = 0; i < e.count; ++i) {
      Vec3 p = Vec3::Zero();
      for (std::size_t k = 0; k < e.properties.size(); ++k) {
        const PlyProperty& prop = e.properties[k];
        if (!prop.is_list) {
          const double x = reader.read(prop.type);
          for (int a = 0; a < 3; ++a)
            if (static_cast<int>(k) == xyz[a]) p[a] = x;
          continue;
        }
        const double n = reader.read(prop.count_type);
        if (!(n >= 0 && n <= 1e6 && n == std::floor(n))) fail(path, "a list has a bad length");
        corners.clear();
        for (int c = 0; c < static_cast<int>(n); ++c) {
          const double index = reader.read(prop.type);
          if (!(index == std::floor(index) && std::abs(index) < 4.3e9))
            fail(path, "a face index is not a whole number of at most 32 bits");
          corners.push_back(static_cast<std::int64_t>(index));
        }
        if (static_cast<int>(k) == face_list)
          add_polygon(path, mesh, corners, mesh.positions.size());
      }
      if (is_vertex) mesh.positions.push_back(p);
    }
    vertices_read = vertices_read || is_vertex;
  }
  // What follows the last element must be nothing (binary) or white space (ascii): more data
  // means the header's counts are smaller than the file's, and reading only as far as they
  // say would silently give part of the mesh.
  char c = 0;
  while (in.get(c))
    if (format != PlyFormat::kAscii || !std::isspace(static_cast<unsigned char>(c)))
      fail(path,
           "data continues after the last element: the header's counts are smaller "
           "than the data");
  return mesh;
}

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

}  // namespace

TriangleMesh read_triangle_mesh(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) fail(path, "no such file");
  const std::string ext = lower_extension(path);
  TriangleMesh mesh;
  if (ext == ".obj")
    mesh = read_obj(path);
  else if (ext == ".ply")
    mesh = read_ply(path);
  else
    fail(path, "unknown extension '" + ext + "'; use a .obj or .ply file");
  for (std::size_t i = 0; i < mesh.positions.size(); ++i)
    if (!mesh.positions[i].allFinite())
      fail(path, "vertex " + std::to_string(i) + " has a non-finite coordinate");
  if (mesh.triangles.empty()) fail(path, "the file holds no faces");
  return mesh;
}

}  // namespace dynamesh
