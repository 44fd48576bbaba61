#!/bin/sh
# The per-application guides' figures (docs/measurements/presets.md): rrc-sample's
# default run (the temple, 60 frames, a 256-sample reference every 10th frame)
# with the library's presets, with their bases (the default) and without them
# (--no-base), every signal in one run, each figure the mean over --seed 0..3
# of the mean over checkpoints.
#   host_sample/testbed/measure_presets.sh SIZE...   (from the repository root)
# prints one Markdown row per size, application and variant: the RMSE of one
# frame's k samples, of the base alone (soft: the PCSS fallback), of rrc's output
# and of the brute force at 4k in one frame, and the ratios.
# RRC_SAMPLE picks the program (default build/release/bin/rrc-sample), OUT the
# scratch directory (default /tmp/rrc_presets), VARIANTS the variants (default
# "base no-base"), EXTRA more rrc-sample options for every run (a setting tried
# against the presets, e.g. EXTRA="--history-filter catmull_rom").
set -e
bin=${RRC_SAMPLE:-build/release/bin/rrc-sample}
out=${OUT:-/tmp/rrc_presets}
echo "| size | application | variant | one frame (k) | base alone | rrc | brute force (4k) | rrc / 4k | rrc / one frame |"
echo "|---|---|---|---|---|---|---|---|---|"
for size in "$@"; do
    for variant in ${VARIANTS:-base no-base}; do
        flag=
        if [ "$variant" = no-base ]; then flag=--no-base; fi
        for s in 0 1 2 3; do
            echo "measure_presets: $size $variant seed $s" >&2
            # shellcheck disable=SC2086
            $bin --size "$size" --frames 60 --reference-every 10 --no-images --quiet --seed $s $flag ${EXTRA:-} --out "$out/${size}_${variant}_$s" >/dev/null
        done
        for signal in pcf env soft; do
            base_row="$signal, the residual's base alone"
            if [ "$signal" = soft ]; then base_row="soft, PCSS alone"; fi
            for s in 0 1 2 3; do
                cat "$out/${size}_${variant}_$s/summary.md"
            done | awk -F'|' -v sig="$signal" -v base="$base_row" -v size="$size" -v variant="$variant" '
                $2 == " " sig " " { raw += $3; bf += $4; acc += $5; n++ }
                index($2, " " base) == 1 { b += $5; nb++ }
                END {
                    bs = nb ? sprintf("%.4f", b / nb) : "-"
                    printf "| %s | %s | %s | %.4f | %s | %.4f | %.4f | %.2fx | %.2fx |\n", size, sig, variant, raw / n, bs, acc / n, bf / n, acc / bf, acc / raw
                }'
        done
    done
done
