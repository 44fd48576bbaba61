#!/bin/sh
# The blur bound's rows of docs/measurements/PERFORMANCE.md ("The blur bound: what it buys,
# measured"): each configuration's rrc-sample "RMSE accumulated" (and the 4k
# brute force) averaged over --seed 0..3, one signal a run.
#   host_sample/testbed/measure_variants.sh SIZE SIGNAL "OPTIONS" ...   (run from the repository root)
# prints one table row per OPTIONS string (quote each; "" = the preset); with pcf's
# residual on (the preset), a last column: its base alone (summary.md's "pcf, the
# residual's base alone"), averaged the same way.
set -e
size=$1 signal=$2
shift 2
bin=${RRC_SAMPLE:-build/release/bin/rrc-sample}
out=${OUT:-/tmp/rrc_blur_bound}
for opts in "$@"; do
    acc=0 bf=0 base=
    for s in 0 1 2 3; do
        dir=$out/$(echo "$size $signal $opts $s" | tr -c 'A-Za-z0-9.\n' _)
        # shellcheck disable=SC2086
        $bin --size "$size" --frames 60 --reference-every 10 --no-images --quiet --seed $s --signals "$signal" $opts --out "$dir" >/dev/null
        row=$(grep "^| $signal | " "$dir/summary.md" | head -1)
        acc=$(echo "$row" | awk -F'|' -v a="$acc" '{print a + $5}')
        bf=$(echo "$row" | awk -F'|' -v a="$bf" '{print a + $4}')
        b=$(grep "^| $signal, the residual's base alone" "$dir/summary.md" | awk -F'|' '{print $5}')
        if [ -n "$b" ]; then base=$(echo "$b" | awk -v a="${base:-0}" '{print a + $1}'); fi
    done
    echo "$size $signal $opts" | awk -v a="$acc" -v b="$bf" -v c="$base" \
        '{printf "| %s | %.4f | %.4f | %.2fx |", $0, a / 4, b / 4, a / b; if (c != "") printf " %.4f |", c / 4; printf "\n"}'
done
