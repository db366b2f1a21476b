// A MeshSnapshot's arrays on the GPU (one vertex array object, dynamic buffers). Uploads
// happen once per new snapshot, never per frame; when the connectivity is unchanged (a
// deforming mesh between structural changes) only positions and normals are sent.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/adapt/mesh_snapshot.h"

namespace dynamesh {

// How often each kind of upload happened (tests and statistics read these).
struct UploadCounters {
  int full = 0;      // positions, normals and triangles
  int geometry = 0;  // positions and normals only (same connectivity)
  int scalar = 0;    // the colour-mode field
};

class GpuMesh {
 public:
  GpuMesh();
  ~GpuMesh();
  GpuMesh(const GpuMesh&) = delete;
  GpuMesh& operator=(const GpuMesh&) = delete;

  void upload_geometry(const MeshSnapshot& snapshot);
  // One value per vertex; nullptr (or a size mismatch) uploads zeros.
  void upload_scalar(const std::vector<float>* values);
  void draw() const;

  std::size_t n_vertices() const { return n_vertices_; }
  std::size_t n_triangles() const { return indices_.size() / 3; }
  const UploadCounters& counters() const { return counters_; }

 private:
  // Sends `bytes` to `buffer`, in fresh storage (orphaning) that grows with slack.
  static void send(unsigned target, unsigned buffer, std::size_t& capacity, const void* data,
                   std::size_t bytes);

  unsigned vao_ = 0;
  unsigned position_buffer_ = 0, normal_buffer_ = 0, scalar_buffer_ = 0, index_buffer_ = 0;
  std::size_t position_capacity_ = 0, normal_capacity_ = 0, scalar_capacity_ = 0,
              index_capacity_ = 0;
  std::size_t n_vertices_ = 0;
  std::vector<std::uint32_t> indices_;  // the uploaded connectivity, to detect changes
  UploadCounters counters_;
};

}  // namespace dynamesh
