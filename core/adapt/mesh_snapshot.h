// MeshSnapshot: a compact, read-only copy of the adapted mesh at the end of a step — the only
// thing renderers and exporters see (data flows surface -> adapter -> snapshot -> renderer).
// Live vertices are renumbered 0..n-1; per-vertex scalar fields ride along by name.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/geometry/vector_types.h"
#include "core/mesh/mesh48.h"
#include "core/surface/volume/volume_image.h"

namespace dynamesh {

struct ScalarField {
  std::string name;           // "error", "curvature", "valence", "level", "intensity", ...
  std::vector<float> values;  // one per snapshot vertex
};

struct MeshSnapshot {
  std::vector<float> positions;          // 3 per vertex
  std::vector<float> normals;            // 3 per vertex (unit)
  std::vector<std::uint32_t> triangles;  // 3 per face, counter-clockwise seen from outside
  std::vector<ScalarField> fields;
  // The scan the surface came from (mri), shared and immutable: null for analytic scenes.
  std::shared_ptr<const VolumeImage> volume;
  Box3 bounds;
  double time = 0.0;
  std::uint64_t step = 0;

  std::size_t n_vertices() const { return positions.size() / 3; }
  std::size_t n_triangles() const { return triangles.size() / 3; }
  // nullptr when absent.
  const ScalarField* field(const std::string& name) const;
};

// Compacts the mesh's live elements; normals are area-weighted face normals unless
// `vertex_normals` (indexed by vertex id) is given. `vertex_fields` are indexed by vertex id
// and renamed to the compact numbering.
MeshSnapshot make_snapshot(const Mesh48& mesh, const std::vector<Vec3>* vertex_normals = nullptr,
                           const std::vector<ScalarField>& vertex_fields = {});

}  // namespace dynamesh
