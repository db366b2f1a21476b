#!/usr/bin/env bash
# Soak (issue 15): runs each analytic scene for STEPS steps (default 10000) through
# dynamesh-cli and samples its resident memory (VmRSS) once a second as it runs, against the
# step its --stats CSV has reached.
#
# The scene goes back and forth over its whole animation (keyframes 0,1,0,...,0, STEPS/20
# steps per segment), so step 1000 and step STEPS are both at t = 0 after full cycles: the
# mesh is the same size there and any growth of the resident memory or of the time per step
# between them is the program's, not the scene's (a single 0 -> 1 pass would compare a small
# sphere at t = 0.1 with a big one at t = 1). The bar: RSS at the last step within 5% of
# step 1000.
#
# Prints one line per scene: RSS near step 1000 and at the end and their ratio, the
# triangles at both steps, and the mean time per step of cycle 2 against the last cycle.
# Not part of CI: at full length it takes tens of minutes per scene.
#   scripts/soak.sh [STEPS] [SCENE...]   (BUILD_DIR, default build; SOAK_DIR keeps the logs;
#   SOAK_ARGS: more dynamesh-cli options, e.g. "--param R1=2" for a smaller sphere)
set -euo pipefail
cd "$(dirname "$0")/.."
steps=${1:-10000}
shift || true
scenes=("$@")
[ ${#scenes[@]} -eq 0 ] && scenes=(sphere capsule-bend sinc twist blobs)
if [ $((steps % 20)) -ne 0 ] || [ "$steps" -lt 2000 ]; then
  echo "soak.sh: STEPS must be a multiple of 20, at least 2000 (got $steps)" >&2
  exit 2
fi
per_segment=$((steps / 20))
keyframes=0
for _ in $(seq 1 10); do keyframes+=",1,0"; done
cli=${BUILD_DIR:-build}/dynamesh-cli
out=${SOAK_DIR:-$(mktemp -d)}
mkdir -p "$out"
for scene in "${scenes[@]}"; do
  csv=$out/$scene.csv
  log=$out/$scene.rss
  # shellcheck disable=SC2086 # SOAK_ARGS is a list of options
  "$cli" run --scene "$scene" --keyframes "$keyframes" --steps "$per_segment" --quiet ${SOAK_ARGS:-} \
    --stats "$csv" >"$out/$scene.json" 2>"$out/$scene.err" &
  pid=$!
  : >"$log"
  start=$(date +%s)
  while kill -0 "$pid" 2>/dev/null; do
    rss=$(awk '/^VmRSS/ {print $2}' /proc/$pid/status 2>/dev/null || true)
    lines=0
    if [ -f "$csv.partial" ]; then lines=$(wc -l <"$csv.partial"); fi
    [ -n "$rss" ] && echo "$(($(date +%s) - start)) $lines $rss" >>"$log"
    sleep 1
  done
  wait "$pid" || { echo "$scene: dynamesh-cli failed, see $out/$scene.err" >&2; continue; }
  # RSS log rows: seconds, CSV lines written (header + steps done), RSS kB. The CSV is
  # buffered, so a row's step lags by at most a few dozen steps.
  awk -F, -v first=1000 -v last="$steps" -v seg="$per_segment" '
    NR == 1 { next }
    { step = $1; tri[step] = $3; sec = $20
      cycle = int((step - 1) / (2 * seg)) + 1
      if (step >= 1 && cycle == 2) { a += sec; na++ }
      if (step >= 1 && step > last - 2 * seg) { b += sec; nb++ } }
    END { printf "%d %d %.5f %.5f\n", tri[first], tri[last], a / na, b / nb }' "$csv" >"$out/$scene.steps"
  read -r tri_first tri_last sec_first sec_last <"$out/$scene.steps"
  awk -v scene="$scene" -v steps="$steps" -v t1="$tri_first" -v t2="$tri_last" \
    -v s1="$sec_first" -v s2="$sec_last" '
    { s = $2 - 1; if (s >= 1000 && at1000 == "") at1000 = $3; if ($3 > peak) peak = $3
      last = $3; t = $1 }
    END {
      if (at1000 == "") { printf "%s: ended before step 1000 (last RSS %d kB)\n", scene, last; exit }
      printf "%s: %d steps in %d s; RSS at step 1000: %d kB, at step %d: %d kB (ratio %.3f, peak %d kB); triangles %d / %d; s/step cycle 2: %.5f, last cycle: %.5f (ratio %.3f)\n",
             scene, steps, t, at1000, steps, last, last / at1000, peak, t1, t2, s1, s2, s2 / s1 }' "$log"
done
[ -n "${SOAK_DIR:-}" ] || rm -rf "$out"
