// VTK XML output for ParaView: one PolyData file (.vtp) per frame and a collection (.pvd)
// naming the frames with their times, so `--export DIR` opens in ParaView as an animation.
// ParaView's collection reader reads VTK XML files only, which is why the frames come as
// .vtp beside the PLY ones (their geometry and fields are the same).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/adapt/mesh_snapshot.h"

namespace dynamesh {

// Points, normals, triangles and every per-vertex field, ASCII (atomic, as AtomicFile).
void write_vtp(const std::string& path, const MeshSnapshot& mesh);

// A collection: (time, file name relative to the .pvd) per frame, in order.
void write_pvd(const std::string& path, const std::vector<std::pair<double, std::string>>& frames);

}  // namespace dynamesh
