#include "core/io/stats_csv.h"

namespace dynamesh {

const char* StatsCsvWriter::header() {
  return "step,time,triangles,vertices,splits,welds,total_splits,total_welds,max_error,"
         "mean_error,samples,vertices_kept,projection_failures,budget_hit,seconds_project,"
         "seconds_smooth,seconds_sample,seconds_weld,seconds_split,seconds_total,kept_fraction,"
         "survivor_displacement_mean,survivor_displacement_max,smoothing_moved,smoothing_reverted,"
         "splits_refused,pathological_welds,substeps,motion_strain,folds_found,slivers_found,"
         "repair_moves,folds_left,slivers_left,faces_measured,topology_events,rebuilt,seconds_"
         "topology,renumbered,seconds_renumber";
}

StatsCsvWriter::StatsCsvWriter(const std::string& path) : file_(path) {
  file_.stream().precision(10);
  file_.stream() << header() << '\n';
}

void StatsCsvWriter::write(const StepStats& s, std::size_t total_splits, std::size_t total_welds) {
  std::ostream& out = file_.stream();
  out << s.step << ',' << s.time << ',' << s.triangles << ',' << s.vertices << ',' << s.splits
      << ',' << s.welds << ',' << total_splits << ',' << total_welds << ',' << s.max_error << ','
      << s.mean_error << ',' << s.samples << ',' << s.vertices_kept << ',' << s.projection_failures
      << ',' << (s.budget_hit ? 1 : 0) << ',' << s.seconds.project << ',' << s.seconds.smooth << ','
      << s.seconds.sample << ',' << s.seconds.weld << ',' << s.seconds.split << ','
      << s.seconds.total << ',' << s.kept_fraction << ',' << s.survivor_displacement_mean << ','
      << s.survivor_displacement_max << ',' << s.smoothing_moved << ',' << s.smoothing_reverted
      << ',' << s.splits_refused << ',' << s.pathological_welds << ',' << s.substeps << ','
      << s.motion_strain << ',' << s.folds_found << ',' << s.slivers_found << ',' << s.repair_moves
      << ',' << s.folds_left << ',' << s.slivers_left << ',' << s.faces_measured << ','
      << s.topology_events.size() << ',' << (s.rebuilt ? 1 : 0) << ',' << s.topology_seconds << ','
      << (s.renumbered ? 1 : 0) << ',' << s.seconds.renumber << '\n';
}

void StatsCsvWriter::close() {
  file_.commit();
}

}  // namespace dynamesh
