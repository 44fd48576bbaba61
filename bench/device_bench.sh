#!/usr/bin/env bash
# rrc-bench through a GPU's Vulkan driver, at 1080p and 4K (docs/measurements/PERFORMANCE.md,
# "A GPU").  Two halves:
#   bash bench/device_bench.sh prepare [BUILD_DIR]   here, on the Debian bookworm build machine:
#       gathers what a bare GPU machine lacks into two git-ignored folders, .gl (the Vulkan
#       loader and GL dispatch packages, amd64) and .gpu (rrc-bench, librrc, this libstdc++)
#   bash bench/device_bench.sh run                   there, from the repository root, with .gl
#       and .gpu carried along: unpacks the loader, runs the benches, writes under $OUT
#       (default out/device): default/ (the default run), 1080/ and 4k/ (the frame plan's
#       rows, 15 repetitions), each with report.md and bench.csv
# RRC_BENCH_DEVICE picks the device by name (default NVIDIA).
set -euo pipefail
case "${1:-}" in
prepare)
    build=${2:-build/release}
    [ -x "$build/bin/rrc-bench" ] || { echo "device_bench.sh: no $build/bin/rrc-bench; build it first" >&2; exit 1; }
    exclude=$(git rev-parse --git-dir)/info/exclude
    mkdir -p "$(dirname "$exclude")" .gl .gpu /tmp/amd64/partial
    for d in .gl .gpu; do grep -qx "/$d/" "$exclude" 2>/dev/null || echo "/$d/" >>"$exclude"; done
    o='-oAPT::Architecture=amd64 -oAPT::Architectures=amd64 -oDir::State::Lists=/tmp/amd64'
    apt-get $o update -qq
    (cd .gl && apt-get $o download libvulkan1 libegl1 libglvnd0 libopengl0 libgl1 libglx0 libgles2)
    cp "$build/bin/rrc-bench" .gpu/
    cp -L "$build/plugin/librrc.so.0" /lib/x86_64-linux-gnu/libstdc++.so.6 /lib/x86_64-linux-gnu/libgcc_s.so.1 .gpu/
    echo "device_bench.sh: .gl and .gpu ready ($(du -sh .gl .gpu | awk '{print $1}' | paste -sd+)); carry both"
    ;;
run)
    for f in .gl/*.deb; do dpkg -x "$f" /; done
    ldconfig
    export LD_LIBRARY_PATH=$PWD/.gpu
    icd=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
    if [ -f "$icd" ]; then export VK_DRIVER_FILES=$icd; fi
    out=${OUT:-out/device}
    dev=${RRC_BENCH_DEVICE:-NVIDIA}
    nvidia-smi --query-gpu=name,driver_version,clocks.max.sm,clocks.max.mem --format=csv || true
    rows=base,depth_fixed,cache_1x4,cache_1x4_copy,cache_1x4_fused,cache_1x4_classify_fused,young12,young12_fill,young12_fill_r1
    .gpu/rrc-bench --device "$dev" --no-plot --out "$out/default"
    .gpu/rrc-bench --device "$dev" --no-plot --config "$rows" --reps 15 --out "$out/1080"
    .gpu/rrc-bench --device "$dev" --no-plot --config "$rows" --reps 15 --size 3840x2160 --out "$out/4k"
    rm -f "$out"/*/bench.json  # the device tool returns at most 8 files
    ;;
*)
    echo "usage: bash bench/device_bench.sh prepare [BUILD_DIR] | run" >&2
    exit 2
    ;;
esac
