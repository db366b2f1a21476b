# Plots of the re-meshing comparison (bench/compare_openvdb.cpp) for the README:
#   gnuplot -e "csv='docs/comparison/comparison.csv'; out='docs/comparison'" bench/plot_comparison.gp
# One panel per scene; x is the dense L-infinity error (both meshes measured alike), so a
# curve further down-left is better. dynamesh's points are its thresholds T, OpenVDB's its
# voxel sizes.
if (!exists("csv")) csv = 'comparison.csv'
if (!exists("out")) out = '.'
set datafile separator ','
set terminal pngcairo size 1500,460 font ',11'
set key top right
set grid
set logscale x
set xlabel 'dense L-infinity error'
set format x '%.0e'
scenes = 'sphere capsule-bend twist'
is(m, s) = (strcol(1) eq m && strcol(2) eq s)
pick(m, s, c) = is(m, s) ? column(c) : NaN

set output out.'/triangles.png'
set multiplot layout 1,3 title 'Triangles per frame (mean over the animation) against error'
set logscale y
set ylabel 'triangles'
do for [s in scenes] {
  set title s
  plot csv skip 1 using (pick('dynamesh', s, 8)):(pick('dynamesh', s, 6)) w lp pt 7 lw 2 t 'dynamesh (T)', \
       csv skip 1 using (pick('openvdb', s, 8)):(pick('openvdb', s, 6)) w lp pt 5 lw 2 t 'OpenVDB re-meshing (voxel size)'
}
unset multiplot

set output out.'/time.png'
set multiplot layout 1,3 title 'CPU time per frame (median, one thread each) against error'
set ylabel 'CPU seconds per frame'
do for [s in scenes] {
  set title s
  plot csv skip 1 using (pick('dynamesh', s, 8)):(pick('dynamesh', s, 9)) w lp pt 7 lw 2 t 'dynamesh step', \
       csv skip 1 using (pick('openvdb', s, 8)):(pick('openvdb', s, 9)) w lp pt 5 lw 2 t 'OpenVDB: grid + volumeToMesh', \
       csv skip 1 using (pick('openvdb', s, 8)):(pick('openvdb', s, 10)) w lp pt 4 dt 2 t 'OpenVDB: grid fill alone'
}
unset multiplot

set output out.'/survival.png'
set multiplot layout 1,3 title 'Vertices kept from one frame to the next (mean over the animation)'
unset logscale y
set yrange [-0.05:1.05]
set ylabel 'share of the previous frame''s vertices'
set key center right
do for [s in scenes] {
  set title s
  plot csv skip 1 using (pick('dynamesh', s, 8)):(pick('dynamesh', s, 12)) w lp pt 7 lw 2 t 'dynamesh', \
       csv skip 1 using (pick('openvdb', s, 8)):(pick('openvdb', s, 12)) w lp pt 5 lw 2 t 'OpenVDB (same position, bitwise)'
}
unset multiplot
