#!/usr/bin/env bash
# Front-end times of two builds of bench_frontend, run alternately (not part
# of CI). On this project's shared 2-core VM the p50 of unchanged code moves
# by up to a third between runs minutes apart, so one run of each build
# cannot tell a 10 % change; runs taken alternately, in the order A B B A
# A B ..., share the machine's slow drift and neither build always goes
# first. Prints, per scene class and resolution, each build's colour-free
# total p50 (ms, wall) in every run and the medians over the runs of its
# segmentation, ROI and total p50s.
#
#   bench/compare_frontend_time.sh OLD_BENCH NEW_BENCH [RUNS] [KINDS] [RESOLUTIONS]
#
# KINDS and RESOLUTIONS are bench_frontend --only lists (defaults: every
# rig class; 640x480,1280x720); RUNS defaults to 3. The builds' answers are
# not compared here: their tables are in the logs under $TMPDIR (stderr of
# each run beside its table).
set -euo pipefail
if (( $# < 2 )); then
  sed -n '2,14p' "$0" >&2
  exit 2
fi
old=$1
new=$2
runs=${3:-3}
kinds=${4:-single,organised_pile,unorganised_pile,touching_rows,pallet_layer,pallet_stack,table_boxes}
resolutions=${5:-640x480,1280x720}
for bench in "$old" "$new"; do
  [[ -f "$bench" && -x "$bench" ]] || { echo "compare_frontend_time: $bench is not an executable file" >&2; exit 2; }
done
old=$(realpath "$old")
new=$(realpath "$new")
# One stage-time row per class and resolution asked for.
expected_rows=$(( $(tr ',' '\n' <<<"$kinds" | grep -c .) * $(tr ',' '\n' <<<"$resolutions" | grep -c .) ))
logs=$(mktemp -d "${TMPDIR:-/tmp}/compare_frontend_time.XXXXXX")
echo "logs: $logs" >&2

# The stage-time table's rows: class | mode | resolution | segmentation | cloud | roi | total.
stageRows() {
  awk -F'|' '/stage times/ { table = 1; next }
             table && /^\| [a-z]/ && !/scene class/ {
               gsub(/^ +| +$/, "", $2); gsub(/^ +| +$/, "", $4)
               printf "%s|%s|%s|%s|%s\n", $2, $4, $5 + 0, $7 + 0, $8 + 0 }
             table && /^$/ && seen++ { table = 0 }' "$1"
}

for (( run = 1; run <= runs; ++run )); do
  sides=(old new)
  (( run % 2 == 0 )) && sides=(new old)
  for side in "${sides[@]}"; do
    bench=$old
    [[ $side == new ]] && bench=$new
    log="$logs/$side.$run.txt"
    "$bench" --frames 100 --only "$kinds" colour_free "$resolutions" --no-mosd >"$log" 2>"$logs/$side.$run.err" ||
      { echo "compare_frontend_time: $bench failed (run $run): $log, $logs/$side.$run.err" >&2; exit 1; }
    rows=$(stageRows "$log")
    if (( $(grep -c . <<<"$rows") != expected_rows )); then
      echo "compare_frontend_time: $log has $(grep -c . <<<"$rows") stage-time rows, not $expected_rows (kinds or resolutions unknown?)" >&2
      exit 1
    fi
    sed "s/^/$side|$run|/" <<<"$rows" >>"$logs/rows.txt"
  done
  echo "run $run of $runs done" >&2
done

# side|run|class|resolution|segmentation|roi|total -> one line per class,
# resolution and side: the runs' totals and the medians of each stage.
printf "%-30s %-9s %-4s %-24s %s\n" class res side "total p50 per run" "median: segmentation / roi / total"
awk -F'|' '
  function median(list,   n, values, i, j, t) {
    n = split(list, values, " ")
    for (i = 1; i <= n; ++i) for (j = i + 1; j <= n; ++j)
      if (values[j] + 0 < values[i] + 0) { t = values[i]; values[i] = values[j]; values[j] = t }
    return n % 2 ? values[(n + 1) / 2] : (values[n / 2] + values[n / 2 + 1]) / 2
  }
  {
    key = $3 "|" $4 "|" $1
    if (!(key in totals)) order[++keys] = key
    segmentation[key] = segmentation[key] " " $5
    roi[key] = roi[key] " " $6
    totals[key] = totals[key] " " $7
  }
  END {
    for (k = 1; k <= keys; ++k) {
      split(order[k], part, "|")
      # Prefixed with a sort key (class, resolution, old before new), cut below.
      printf "%s|%s|%s\t%-30s %-9s %-4s %-24s %.1f / %.1f / %.1f\n", part[1], part[2], part[3] == "old" ? 0 : 1,
             part[1], part[2], part[3], totals[order[k]],
             median(segmentation[order[k]]), median(roi[order[k]]), median(totals[order[k]])
    }
  }' "$logs/rows.txt" | LC_ALL=C sort -t$'\t' -k1,1 | cut -f2-
