#include "app/viewer/widget_report.h"

#include <algorithm>
#include <sstream>

#include "core/geometry/mesh_quality.h"

namespace dynamesh {

double mean_aspect_ratio(const MeshSnapshot& mesh) {
  const auto& p = mesh.positions;
  const auto vertex = [&](std::uint32_t v) { return Vec3(p[3 * v], p[3 * v + 1], p[3 * v + 2]); };
  double sum = 0.0;
  const std::size_t n = mesh.n_triangles();
  for (std::size_t f = 0; f < n; ++f) {
    const std::uint32_t* t = &mesh.triangles[3 * f];
    sum += aspect_ratio(vertex(t[0]), vertex(t[1]), vertex(t[2]));
  }
  return n > 0 ? sum / double(n) : 0.0;
}

std::string widget_report(const std::vector<WidgetRect>& widgets,
                          const SimulationControls& controls, const ShownState& shown) {
  std::ostringstream out;
  out.precision(10);
  for (const WidgetRect& w : widgets) {
    std::string label = w.label;
    std::replace(label.begin(), label.end(), ' ', '_');
    out << "widget " << label << ' ' << w.x0 << ' ' << w.y0 << ' ' << w.x1 << ' ' << w.y1 << '\n';
    if (w.active) out << "active " << label << '\n';
  }
  out << "threshold " << controls.threshold << "\nepsilon " << controls.epsilon << "\ndensity "
      << controls.density << "\nk " << controls.k << "\nsmooth_settled " << controls.smooth_settled
      << "\nresults " << shown.results << "\nbusy " << (shown.busy ? 1 : 0) << '\n';
  out << "frames " << shown.frames << '\n';
  if (!shown.progress.empty()) out << "progress " << shown.progress << '\n';
  if (!shown.scene.empty()) out << "scene " << shown.scene << '\n';
  if (shown.scene_text != nullptr)
    for (const auto& [key, value] : *shown.scene_text)
      out << "scene_text " << key << ' ' << value << '\n';
  for (const auto& [key, message] :
       {std::pair{"error", &shown.error}, std::pair{"open_error", &shown.open_error}}) {
    if (message->empty()) continue;
    std::string one_line = *message;
    std::replace(one_line.begin(), one_line.end(), '\n', ' ');
    out << key << ' ' << one_line << '\n';
  }
  if (shown.mesh != nullptr) {
    const auto& p = shown.mesh->positions;
    Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
    for (std::size_t i = 0; i + 2 < p.size(); i += 3) {
      lo = lo.cwiseMin(Vec3(p[i], p[i + 1], p[i + 2]));
      hi = hi.cwiseMax(Vec3(p[i], p[i + 1], p[i + 2]));
    }
    out << "bounds " << lo.x() << ' ' << lo.y() << ' ' << lo.z() << ' ' << hi.x() << ' ' << hi.y()
        << ' ' << hi.z() << '\n';
    out << "step " << shown.mesh->step << "\ntriangles " << shown.mesh->n_triangles()
        << "\nmean_aspect " << mean_aspect_ratio(*shown.mesh) << "\nsamples " << shown.samples
        << "\nmean_error " << shown.mean_error << '\n';
  }
  if (const VolumeProbe* p = shown.probe) {
    out << "probe " << p->position.x() << ' ' << p->position.y() << ' ' << p->position.z()
        << "\nprobe_voxel " << p->index[0] << ' ' << p->index[1] << ' ' << p->index[2]
        << "\nprobe_intensity " << p->intensity << "\nprobe_depth " << p->depth << "\nprobe_region "
        << p->region << ' ' << p->region_name << '\n';
  }
  return out.str();
}

}  // namespace dynamesh
