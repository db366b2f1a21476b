#!/usr/bin/env bash
# Regenerates the README's comparison with OpenVDB re-meshing (issue 17): builds
# bench/compare_openvdb, runs it (sphere, capsule-bend, twist; every threshold and voxel size;
# 100 frames; about an hour on a 2-core machine) and draws docs/comparison/*.png with gnuplot.
# Extra arguments go to the program (e.g. --scenes twist --frames 20 for a quick look).
# Needs the optional Debian packages libopenvdb-dev and gnuplot-nox (see
# scripts/debian-packages.txt for why ./dev does not install them).
set -euo pipefail
cd "$(dirname "$0")/.."
missing=()
for p in libopenvdb-dev gnuplot-nox; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  if [ "$(id -u)" != 0 ]; then
    echo "compare-openvdb: install first: sudo apt-get install --no-install-recommends ${missing[*]}" >&2
    exit 2
  fi
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
BUILD_DIR=${BUILD_DIR:-build}
OUT=${OUT:-docs/comparison}
cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$BUILD_DIR" -j"$(nproc)" --target compare_openvdb
mkdir -p "$OUT"
{ echo "# $(date -u +%Y-%m-%dT%H:%MZ), $(nproc) cores, load before: $(cut -d' ' -f1-3 /proc/loadavg)"
  "$BUILD_DIR/bench/compare_openvdb" --out "$OUT/comparison.csv" "$@"; } | tee "$OUT/summary.txt"
gnuplot -e "csv='$OUT/comparison.csv'; out='$OUT'" bench/plot_comparison.gp
echo "compare-openvdb: $OUT/comparison.csv, summary.txt, triangles.png, time.png, survival.png" >&2
