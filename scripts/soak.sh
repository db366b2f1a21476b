#!/usr/bin/env bash
# Soak (issue 15): runs each analytic scene for STEPS steps (default 10000) through
# dynamesh-cli and samples its resident memory (VmRSS) as it runs, against the step the
# --stats CSV has reached. Prints one line per scene: RSS near step 1000 and at the end, and
# their ratio (the bar: the end within 5% of step 1000). Not part of CI: at full length it
# takes tens of minutes per scene.
#   scripts/soak.sh [STEPS] [SCENE...]     (BUILD_DIR, default build)
set -euo pipefail
cd "$(dirname "$0")/.."
steps=${1:-10000}
shift || true
scenes=("$@")
[ ${#scenes[@]} -eq 0 ] && scenes=(sphere capsule-bend sinc twist)
cli=${BUILD_DIR:-build}/dynamesh-cli
out=$(mktemp -d)
for scene in "${scenes[@]}"; do
  csv=$out/$scene.csv
  "$cli" run --scene "$scene" --steps "$steps" --quiet --stats "$csv" >"$out/$scene.json" &
  pid=$!
  log=$out/$scene.rss
  : >"$log"
  start=$(date +%s)
  while kill -0 "$pid" 2>/dev/null; do
    rss=$(awk '/^VmRSS/ {print $2}' /proc/$pid/status 2>/dev/null || true)
    done_steps=$( [ -f "$csv.partial" ] && wc -l <"$csv.partial" || { [ -f "$csv" ] && wc -l <"$csv" || echo 0; })
    [ -n "$rss" ] && echo "$(( $(date +%s) - start )) $done_steps $rss" >>"$log"
    sleep 1
  done
  wait "$pid"
  # Rows: seconds, CSV lines (header + steps done + 1), RSS kB.
  awk -v scene="$scene" -v steps="$steps" '
    { s = $2 - 2; if (s >= 1000 && at1000 == "") at1000 = $3; last = $3; lastStep = s; t = $1 }
    END {
      if (at1000 == "") { printf "%s: ended before step 1000 (last RSS %d kB)\n", scene, last; exit }
      printf "%s: %d steps in %d s; RSS at step ~1000: %d kB, at step ~%d: %d kB; ratio %.3f\n",
             scene, steps, t, at1000, lastStep, last, last / at1000 }' "$log"
done
rm -rf "$out"
