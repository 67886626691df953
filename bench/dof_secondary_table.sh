#!/bin/sh
# The dof-secondary measurements of docs/secondary-rays.md ("Error and time"):
# each built-in secondary-ray scene by the Embree one-bounce reference, by
# dof-secondary (CPU build) with the paper's defaults, and by the primary-only
# image; then one parameter at a time (clusters per facet, field of view,
# layer size, lens parts) on mirror-sphere and curved-mirror; then the motion
# seen in a mirror: mirror-motion by 1 to 16 shutter slices
# (--bounce-time-slices) and by the exact bounce. Prints one line
# per render: scene, variant, ms_total, the bounce phase, RMSE and PSNR
# against Embree (8-bit PNGs). Usage:
#   bench/dof_secondary_table.sh build/frontend/blurcull out_folder [size] [spp]
set -eu
blurcull=$1
out=$2
size=${3:-160x120}
spp=${4:-16}
mkdir -p "$out"
here=$(dirname "$0")
field() { python3 -c "import json,sys; d=json.load(sys.stdin); print('%.0f %.0f' % (d['ms_total'], d['ms_per_phase'].get('$1', 0)))"; }
run() {  # scene name backend extra-flags...
    scene=$1; name=$2; backend=$3; shift 3
    times=$("$blurcull" render --scene "$scene" --size "$size" --spp "$spp" --backend "$backend" \
        -o "$out/$scene-$name.png" -q --json "$@" | field bounce)
    if [ "$name" = embree ]; then err="-"; else err=$(python3 "$here/png_metrics.py" "$out/$scene-embree.png" "$out/$scene-$name.png"); fi
    echo "$scene $name ms_total,ms_bounce=$times $err"
}
for scene in mirror-sphere water curved-mirror; do
    run $scene embree embree
    run $scene dof cpu --method dof-secondary
    run $scene primary-only cpu --method dof-secondary --secondary-bounces environment
done
for scene in mirror-sphere curved-mirror; do
    for k in 1 2; do run $scene clusters$k cpu --method dof-secondary --clusters-per-facet $k; done
    for fov in 50 110 140; do run $scene fov$fov cpu --method dof-secondary --secondary-fov $fov; done
    for res in 256 1024; do run $scene size$res cpu --method dof-secondary --layer-size $res; done
    for parts in 1 16; do run $scene parts$parts cpu --method dof-secondary --lens-parts $parts; done
    run $scene layers4 cpu --method dof-secondary --secondary-layers 4
done
run mirror-motion embree embree
for slices in 1 2 4 8 16; do
    run mirror-motion slices$slices cpu --method dof-secondary --bounce-time-slices $slices
done
run mirror-motion exact cpu --method dof-secondary --secondary-bounces exact
