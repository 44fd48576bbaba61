#!/usr/bin/env bash
# Two builds' rrc-bench, interleaved (A B A B ...), so that the machine's drift
# falls on both: each row's kernel time and kernel/roof ratio, every run and the
# median, before (A) and after (B).  A change keeps a row within its spread when
# B's median lies within A's min-max (docs/measurements/PERFORMANCE.md, "One table of channel options, measured").
#
#   bench/compare_builds.sh A/bin/rrc-bench B/bin/rrc-bench [CONFIGS] [RUNS]
#
# CONFIGS: rrc-bench --config names (default base,depth_fixed,young12_fill,cache_1x4);
# RUNS: runs of each build (default 3).  Runs on lavapipe (VK_ICD_FILENAMES) at
# rrc-bench's default size, 1920x1080.
set -euo pipefail
if (($# < 2)); then
  sed -n '2,11p' "$0"
  exit 2
fi
a=$1 b=$2 configs=${3:-base,depth_fixed,young12_fill,cache_1x4} runs=${4:-3}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export VK_ICD_FILENAMES=${VK_ICD_FILENAMES:-/usr/share/vulkan/icd.d/lvp_icd.x86_64.json} XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}
for ((i = 1; i <= runs; ++i)); do
  for side in A B; do
    bin=$a
    [ "$side" = B ] && bin=$b
    echo "compare_builds: run $i of $runs, $side ($bin)" >&2
    "$bin" --config "$configs" --no-plot --out "$work/$side$i" > "$work/$side$i.log" 2>&1 ||
      { cat "$work/$side$i.log" >&2; exit 1; }
  done
done
python3 - "$work" "$runs" "$configs" <<'EOF'
import csv, statistics, sys
work, runs, configs = sys.argv[1], int(sys.argv[2]), sys.argv[3].split(",")
rows = {}
for side in "AB":
    for i in range(1, runs + 1):
        for r in csv.DictReader(open(f"{work}/{side}{i}/bench.csv")):
            rows.setdefault((side, r["name"]), []).append((float(r["kernel_ms_median"]), float(r["ratio_median"])))
print("| row | A kernel ms, each run | B kernel ms, each run | A median | B median | B within A's spread | A ratio median | B ratio median |")
print("|---|---|---|---:|---:|---|---:|---:|")
for n in configs:
    ta, tb = [x[0] for x in rows[("A", n)]], [x[0] for x in rows[("B", n)]]
    ma, mb = statistics.median(ta), statistics.median(tb)
    within = "yes" if mb <= max(ta) else "no (slower)"
    ra, rb = statistics.median(x[1] for x in rows[("A", n)]), statistics.median(x[1] for x in rows[("B", n)])
    print(f"| {n} | {', '.join(f'{t:.1f}' for t in ta)} | {', '.join(f'{t:.1f}' for t in tb)} | {ma:.1f} | {mb:.1f} | {within} | {ra:.3f} | {rb:.3f} |")
EOF
