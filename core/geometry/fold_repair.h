// Fold detection and local repair: no published frame may hold a fold (DESIGN.md, "Quality
// bars": every frame an embedded manifold with a floor on its smallest angle).
//
// A face is *folded* when its normal points against the surface normal at one of its corners
// (implicit: grad F; parametric: Su x Sv). One test covers the three ways motion breaks a mesh:
// a triangle turned over, a triangle stretched over a crease (its corners sit on sheets whose
// normals disagree), and a tangled one-ring (some face of the ring turned over). A face is a
// *sliver* when its smallest angle is below the floor.
//
// Finding them costs one pass over the faces with the mesh alone (face normals against their
// vertices' area-weighted mesh normals, smallest angles); only the few candidates evaluate the
// surface. Repair is local relaxation: each vertex of a bad face moves towards its one-ring's
// centroid in its tangent plane and back onto the surface, kept only if the worst face of its
// star gets better (where the centroid does not help, the best of a few small tangent moves
// around it); rings that stay bad widen to their neighbours, round after round.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/mesh/mesh48.h"
#include "core/surface/surface.h"

namespace dynamesh {

struct FoldRepairOptions {
  bool enabled = true;
  double min_angle_deg = 10.0;  // faces with a smaller angle are relaxed too
  int max_rounds = 12;
  // The adapter's last look before publishing a frame (Adapter::publish_repaired) judges only
  // the faces around vertices whose one-ring a split or weld changed since this step's
  // correction found no bad face (find_bad_faces_around: the same verdicts); false: all faces.
  bool screen_changed_only = true;
  // A step taken in one go whose predicted edge strain (motion_substeps.h) is at most this
  // skips the screen (and repair) right after its correction: the frame's screen before
  // publishing then judges every face, and repairs, re-measures and refines as after any
  // screen, so every published frame is judged as before. Twist at 100 steps has strains of
  // 0.09-0.12 and no bad face before publishing: one full screen per step instead of two.
  // Stronger steps (sub-stepped ones have 0.125-0.25 per sub-step) are screened and repaired
  // before their samples, welds and splits. 0: always screen after correction.
  double prescreen_above_strain = 0.125;
};

struct FoldReport {
  std::size_t folded = 0, slivers = 0;  // found
  std::size_t moved = 0;                // vertex moves kept
  std::size_t remaining_folded = 0, remaining_slivers = 0;
};

// The screen's per-face and per-vertex scratch arrays (about 40 bytes per face and vertex, 40 MB
// at 10^6 triangles), kept by a caller that screens every step: allocated anew on every call
// they were mapped and unmapped each time (blocks this large are mapped on their own,
// allocator_policy.h), and the kernel's page faults and page clearing cost more than the
// screen's arithmetic (issue 17's profile at 10^6 triangles).
struct FoldScreenBuffers {
  std::vector<Vec3> normal;            // per face slot: its area-weighted normal
  std::vector<Vec3> vertex_normal;     // per vertex slot: its faces' normals, summed in face order
  std::vector<double> vertex_normal2;  // per vertex slot: vertex_normal's squared norm
  std::vector<std::uint8_t> kind;      // per face slot: 1 folded, 2 sliver, 0 neither
  // find_bad_faces_around: a face slot or vertex slot is done in this call when its mark
  // equals `call` (bumped once per call, so no array is cleared or sorted between calls).
  std::vector<std::uint32_t> face_mark, vertex_mark;
  std::uint32_t call = 0;
  std::vector<Face> ring;  // one vertex's faces, in face order
};

// Whether face f is folded (above): its normal points away from the surface normal at one of
// its corners (or it has none).
bool folded_against_surface(const Mesh48& mesh, const Surface& surface, Face f);

// Faces that are folded (`folded`) or slivers (`slivers`), checked as described above.
// `buffers`: scratch kept between calls (none: allocated for this call); same verdicts.
void find_bad_faces(const Mesh48& mesh, const Surface& surface, double min_angle_deg,
                    std::vector<Face>& folded, std::vector<Face>& slivers,
                    FoldScreenBuffers* buffers = nullptr);

// find_bad_faces' verdicts on the faces with a corner in `vertices` only, bit for bit (each
// corner's mesh normal is summed over its faces in the same order). Where only those
// vertices' one-rings changed since a find_bad_faces that found no bad face (splits and welds
// moving no vertex), this is what a full find_bad_faces would find.
// `vertices` may repeat (each is judged once); `buffers` as for find_bad_faces.
void find_bad_faces_around(const Mesh48& mesh, const Surface& surface, double min_angle_deg,
                           const std::vector<Vertex>& vertices, std::vector<Face>& folded,
                           std::vector<Face>& slivers, FoldScreenBuffers* buffers = nullptr);

FoldReport repair_folds(Mesh48& mesh, const Surface& surface, const FoldRepairOptions& options,
                        FoldScreenBuffers* buffers = nullptr);

}  // namespace dynamesh
