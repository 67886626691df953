#!/bin/sh
# Layer building and bouncing of dof-secondary, host against GL
# (docs/secondary-rays.md, "What the gl backend runs"): each built-in
# secondary-ray scene on the gl backend with the layers built by the GL
# passes and the rays clipped, traced and their surfaces picked there
# (--layer-images gl, the default), with the same GL layers read back for the
# host's clipping around the GL trace pass (--layer-images gl-readback), and
# by the host code (--layer-images host; all three run the clusters one at a
# time on one thread), and by the cpu backend (clusters on every thread).
# Prints per render: ms_total, the bounce phase (ms_per_phase.bounce: the
# clusters' views, layers, clipping, traces and shading), the summed
# layer-build time (counters.layer_build_ms; with gl it includes the
# clipping and traces), the trace steps, and the RMSE / PSNR of the image
# against the cpu backend's. Usage:
#   bench/dof_secondary_gl_layers.sh build/frontend/blurcull out_folder [size] [spp]
set -eu
blurcull=$1
out=$2
size=${3:-200x150}
spp=${4:-16}
mkdir -p "$out"
here=$(dirname "$0")
fields() { python3 -c "import json,sys; d=json.load(sys.stdin); c=d['counters']; print('ms_total=%.0f bounce_ms=%.0f layer_build_ms=%.0f trace_steps=%d fragments=%d' % (d['ms_total'], d['ms_per_phase']['bounce'], c['layer_build_ms'], c['trace_steps'], c['layer_fragments']))"; }
run() {  # scene name backend extra-flags...
    scene=$1; name=$2; backend=$3; shift 3
    result=$("$blurcull" render --scene "$scene" --size "$size" --spp "$spp" --backend "$backend" --method dof-secondary \
        -o "$out/$scene-$name.png" -q --json "$@" | fields)
    if [ "$name" = cpu ]; then err="-"; else err=$(python3 "$here/png_metrics.py" "$out/$scene-cpu.png" "$out/$scene-$name.png"); fi
    echo "$scene $name $result $err"
}
uptime
for scene in mirror-sphere water curved-mirror; do
    run $scene cpu cpu
    run $scene gl-layers gl --layer-images gl
    run $scene gl-readback gl --layer-images gl-readback
    run $scene host-layers gl --layer-images host
done
uptime
