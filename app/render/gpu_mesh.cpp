#include "app/render/gpu_mesh.h"

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

#include "app/render/gl_api.h"

namespace dynamesh {
namespace {

// Area-weighted vertex normals, for snapshots that come without normals.
std::vector<float> vertex_normals(const MeshSnapshot& s) {
  std::vector<float> n(s.positions.size(), 0.0f);
  const auto p = [&s](std::uint32_t v) {
    return glm::vec3(s.positions[3 * v], s.positions[3 * v + 1], s.positions[3 * v + 2]);
  };
  for (std::size_t t = 0; t + 2 < s.triangles.size(); t += 3) {
    const std::uint32_t a = s.triangles[t], b = s.triangles[t + 1], c = s.triangles[t + 2];
    const glm::vec3 face = glm::cross(p(b) - p(a), p(c) - p(a));
    for (std::uint32_t v : {a, b, c}) {
      for (int k = 0; k < 3; ++k) n[3 * v + k] += face[k];
    }
  }
  for (std::size_t v = 0; v + 2 < n.size(); v += 3) {
    const float len = std::sqrt(n[v] * n[v] + n[v + 1] * n[v + 1] + n[v + 2] * n[v + 2]);
    if (len > 0.0f) {
      for (int k = 0; k < 3; ++k) n[v + k] /= len;
    }
  }
  return n;
}

}  // namespace

GpuMesh::GpuMesh() {
  gl::GenVertexArrays(1, &vao_);
  unsigned buffers[4];
  gl::GenBuffers(4, buffers);
  position_buffer_ = buffers[0];
  normal_buffer_ = buffers[1];
  scalar_buffer_ = buffers[2];
  index_buffer_ = buffers[3];
  // Attribute layout is fixed once; only buffer contents change later.
  gl::BindVertexArray(vao_);
  const unsigned per_attribute[3] = {position_buffer_, normal_buffer_, scalar_buffer_};
  const int components[3] = {3, 3, 1};
  for (unsigned i = 0; i < 3; ++i) {
    gl::BindBuffer(GL_ARRAY_BUFFER, per_attribute[i]);
    gl::EnableVertexAttribArray(i);
    gl::VertexAttribPointer(i, components[i], GL_FLOAT, GL_FALSE, 0, nullptr);
  }
  gl::BindBuffer(GL_ELEMENT_ARRAY_BUFFER, index_buffer_);
  gl::BindVertexArray(0);
}

GpuMesh::~GpuMesh() {
  const unsigned buffers[4] = {position_buffer_, normal_buffer_, scalar_buffer_, index_buffer_};
  gl::DeleteBuffers(4, buffers);
  gl::DeleteVertexArrays(1, &vao_);
}

void GpuMesh::send(unsigned target, unsigned buffer, std::size_t& capacity, const void* data,
                   std::size_t bytes) {
  gl::BindBuffer(target, buffer);
  // Grow with slack so that a slowly refining mesh does not outgrow its buffer every step.
  if (bytes > capacity) capacity = std::max(bytes, capacity + capacity / 2);
  // Fresh storage every time (orphaning): the frame still drawing from the old contents
  // keeps them, and this upload does not wait for it to finish.
  gl::BufferData(target, static_cast<GLsizeiptr>(capacity), nullptr, GL_DYNAMIC_DRAW);
  if (bytes > 0) gl::BufferSubData(target, 0, static_cast<GLsizeiptr>(bytes), data);
}

void GpuMesh::upload_geometry(const MeshSnapshot& s) {
  const std::size_t nv = s.n_vertices();
  const bool same_connectivity = nv == n_vertices_ && s.triangles == indices_;
  gl::BindVertexArray(vao_);  // the element buffer binding belongs to the VAO
  send(GL_ARRAY_BUFFER, position_buffer_, position_capacity_, s.positions.data(),
       s.positions.size() * sizeof(float));
  const std::vector<float> computed =
      s.normals.size() == s.positions.size() ? std::vector<float>{} : vertex_normals(s);
  const std::vector<float>& normals = computed.empty() ? s.normals : computed;
  send(GL_ARRAY_BUFFER, normal_buffer_, normal_capacity_, normals.data(),
       normals.size() * sizeof(float));
  if (same_connectivity) {
    ++counters_.geometry;
  } else {
    indices_ = s.triangles;
    send(GL_ELEMENT_ARRAY_BUFFER, index_buffer_, index_capacity_, indices_.data(),
         indices_.size() * sizeof(std::uint32_t));
    ++counters_.full;
  }
  gl::BindVertexArray(0);
  n_vertices_ = nv;
}

void GpuMesh::upload_scalar(const std::vector<float>* values) {
  std::vector<float> zeros;
  if (values == nullptr || values->size() != n_vertices_) {
    zeros.assign(n_vertices_, 0.0f);
    values = &zeros;
  }
  send(GL_ARRAY_BUFFER, scalar_buffer_, scalar_capacity_, values->data(),
       values->size() * sizeof(float));
  ++counters_.scalar;
}

void GpuMesh::draw() const {
  if (indices_.empty()) return;
  gl::BindVertexArray(vao_);
  gl::DrawElements(GL_TRIANGLES, static_cast<GLsizei>(indices_.size()), GL_UNSIGNED_INT, nullptr);
  gl::BindVertexArray(0);
}

}  // namespace dynamesh
