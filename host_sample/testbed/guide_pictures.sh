#!/bin/sh
# The pictures of README.md and the per-application guides (docs/guide/img/): crops of one
# frame side by side, made with OpenImageIO's oiiotool from the programs' own
# outputs.
#   readme (README.md's picture): pcf's one frame, rrc's output and the reference;
#   pcf, env, soft: rrc-sample at 1024x640, seed 0, its presets with their bases,
#     frame 59 (a checkpoint): one frame's samples, rrc's output, the brute force at
#     4x the samples, the reference (exr/<signal>_0059.exr's layers);
#   cache: rrc-cache at 1024x640, TILED n = 4: every pixel shaded, the cache, its
#     coherence map;
#   offline: rrc-accumulate --preset blender on tests/data/offline: Cycles' 4-sample
#     frame 3 and rrc's output, enlarged 4x.
#   host_sample/testbed/guide_pictures.sh [BIN_DIR]   (from the repository root; default build/release/bin)
set -e
bin=${1:-build/release/bin}
out=${OUT:-/tmp/rrc_guide_pictures}
img=docs/guide/img
mkdir -p "$out" "$img"
"$bin/rrc-sample" --size 1024x640 --frames 60 --reference-every 10 --seed 0 --quiet --out "$out/sample" >/dev/null
# crop SIGNAL CHANNELS WxH+X+Y: the four layers' crops in a row, 4 px apart.
crop() {
    exr="$out/sample/exr/$1_0059.exr"
    for layer in raw accumulated brute_force_4x reference; do
        chans=$(echo "$2" | sed "s/\([A-Z]\)/$layer.\1/g")
        oiiotool "$exr" --ch "$chans" --cut "$3" --clamp:min=0:max=1 -d uint8 -o "$out/$1_$layer.png"
    done
    oiiotool "$out/$1_raw.png" "$out/$1_accumulated.png" "$out/$1_brute_force_4x.png" "$out/$1_reference.png" \
        --mosaic:pad=4 4x1 -o "$img/$1.png"
}
crop pcf "Y,Y,Y" 320x200+540+340
oiiotool "$out/pcf_raw.png" "$out/pcf_accumulated.png" "$out/pcf_reference.png" --mosaic:pad=4 3x1 -o "$img/readme.png"
crop soft "Y,Y,Y" 320x200+540+340
crop env "R,G,B" 256x200+130+280
"$bin/rrc-cache" --size 1024x640 --frames 24 --periods 4 --policies tiled --no-stereo --octaves 8 --no-plot --out "$out/cache" >/dev/null
for name in full cached coherence; do
    oiiotool "$out/cache/$name.png" --cut 320x200+100+260 -o "$out/cache_$name.png"
done
oiiotool "$out/cache_full.png" "$out/cache_cached.png" "$out/cache_coherence.png" --mosaic:pad=4 3x1 -o "$img/cache.png"
mkdir -p "$out/offline"
"$bin/rrc-accumulate" --preset blender --input tests/data/offline/blender_cycles_%04d.exr --frames 1-3 \
    --output "$out/offline/%04d.exr" --quiet >/dev/null
oiiotool tests/data/offline/blender_cycles_0003.exr --ch R=ViewLayer.Combined.R,G=ViewLayer.Combined.G,B=ViewLayer.Combined.B \
    --resize:filter=box 256x192 --colorconvert linear sRGB --clamp:min=0:max=1 -d uint8 -o "$out/offline_in.png"
oiiotool "$out/offline/0003.exr" --ch R=ViewLayer.Combined.R,G=ViewLayer.Combined.G,B=ViewLayer.Combined.B \
    --resize:filter=box 256x192 --colorconvert linear sRGB --clamp:min=0:max=1 -d uint8 -o "$out/offline_out.png"
oiiotool "$out/offline_in.png" "$out/offline_out.png" --mosaic:pad=4 2x1 -o "$img/offline.png"
echo "guide_pictures: $(ls "$img" | tr '\n' ' ')in $img"
