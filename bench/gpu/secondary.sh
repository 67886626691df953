#!/usr/bin/env bash
# Issue 24's bench: dof-secondary on the gl backend with the GPU-resident
# bounce (--layer-images gl: layers, clipping, traces and surfaces on the
# GPU), the same with the primary pass on the compute pipeline
# (gl-compute), with the same GL layers read back for the host's clipping
# (--layer-images gl-readback, the previous build), and embree's exact bounce
# with every thread, on the built-in secondary-ray scenes, in one run; then
# the JCST configuration (water, 800x600, 100 spp) beside the paper's 196 ms
# on a GTX 285. Prints per render the whole time, the primary pass and the
# resolve and bounce phases (host clock: wall time, GL work included), of the
# bounce the host's own steps (clustering, views, shading; on the gl and
# gl-compute variants the clustering is the GPU's compute passes, waited
# for), on hardware GL the resident bounce's GPU time (gpu_bounce_layers +
# gpu_bounce_trace + gpu_bounce_gpu_clustering, and gl-compute's resolve on
# the GPU, gpu_primary_resolve; timer queries), and the PSNR
# against embree. The gl-compute variant scans the
# layers in compute as well (GlLayerRaster::compute), gl on the GL rasterizer. docs/secondary-rays.md, "What the gl backend runs".
#
# Build and pack here, then run from the bundle on the device:
#   cmake --build build
#   bash ../shared/gpu/bundle.sh build blurcull
#   bash .gpu/env.sh bash bench/gpu/secondary.sh      (carry [".gpu"])
# Here (llvmpipe) it is a smoke run, labelled software: 100x75, 4 spp, no
# JCST line, unless BENCH_SIZE, BENCH_SPP, BENCH_RUNS say otherwise. On a
# hardware GPU: 1024x768, 16 spp, 3 runs each (medians). Writes
# secondary.csv and secondary-summary.txt under $OUT (or ./gpu-bench);
# exits non-zero if a render failed.
set -u
script=secondary.sh
summary_name=secondary-summary.txt
# shellcheck source=bench/gpu/bench_common.sh
. "$(dirname "$0")/bench_common.sh"
here=$(cd "$(dirname "$0")/.." && pwd)
csv=$dest/secondary.csv

probe_gl --scene mirror-sphere
if [ "$kind" = software ]; then def_size=100x75; def_spp=4; def_runs=1; else def_size=1024x768; def_spp=16; def_runs=3; fi
size=${BENCH_SIZE:-$def_size}
spp=${BENCH_SPP:-$def_spp}
runs=${BENCH_RUNS:-$def_runs}
say_machine
say "gl: $renderer ($kind)"
say "cpus: $(nproc); size $size, spp $spp, runs $runs, seed 1, sampler sobol"
[ "$kind" = software ] && say "SOFTWARE GL (llvmpipe on the CPU): a smoke run, not GPU figures"

echo "scene,variant,size,spp,run,ms_total,ms_primary,ms_resolve,ms_bounce,host_clustering,host_views,host_shading,gpu_bounce_layers,gpu_bounce_trace,gpu_bounce_clustering,gpu_primary_resolve,psnr_db" >"$csv"
failed=0
# One render: scene variant size spp run args...; appends a csv line.
render() {
  local scene=$1 variant=$2 sz=$3 n=$4 run=$5
  shift 5
  if ! "$blurcull" render --scene "$scene" --size "$sz" --spp "$n" --json -q -o "$work/$scene-$sz-$variant.png" "$@" \
       >"$work/out.json" 2>"$work/err.txt"; then
    say "$scene $variant $sz: FAILED: $(head -c 300 "$work/err.txt")"
    failed=$((failed + 1))
    return
  fi
  local psnr=-
  [ "$variant" = embree ] || psnr=$(python3 "$here/png_metrics.py" "$work/$scene-$sz-embree.png" \
                                     "$work/$scene-$sz-$variant.png" | sed -n 's/.*psnr=\([0-9.a-z]*\)dB.*/\1/p')
  python3 - "$scene" "$variant" "$sz" "$n" "$run" "$psnr" "$work/out.json" >>"$csv" <<'PY'
import json, sys
scene, variant, size, spp, run, psnr, path = sys.argv[1:8]
d = json.load(open(path))
p = d.get("ms_per_phase", {})
own = ("resolve", "bounce", "compile")  # and the wall_ / gpu_ parts of bounce
primary = sum(v for k, v in p.items() if k not in own and not k.startswith(("gpu_", "wall_")))
gpu = lambda k: "%.2f" % p[k] if k in p else ""
print(",".join([scene, variant, size, spp, run, "%.1f" % d["ms_total"], "%.1f" % primary,
                "%.1f" % p.get("resolve", 0.0), "%.1f" % p.get("bounce", 0.0), gpu("wall_bounce_clustering"),
                gpu("wall_bounce_views"), gpu("wall_bounce_shading"), gpu("gpu_bounce_layers"),
                gpu("gpu_bounce_trace"), gpu("gpu_bounce_gpu_clustering"), gpu("gpu_primary_resolve"), psnr]))
PY
}
# Every variant of one scene and size, embree first (the reference image).
scene_runs() {
  local scene=$1 sz=$2 n=$3
  for run in $(seq 1 "$runs"); do
    render "$scene" embree "$sz" "$n" "$run" --backend embree
    render "$scene" gl "$sz" "$n" "$run" --backend gl --method dof-secondary --layer-images gl
    render "$scene" gl-compute "$sz" "$n" "$run" --backend gl --gl-pipeline compute --method dof-secondary
    render "$scene" gl-readback "$sz" "$n" "$run" --backend gl --method dof-secondary --layer-images gl-readback
  done
}
# The table of every scene measured so far, rebuilt after each (a run cut
# off by its budget keeps the scenes it finished).
table=$work/table.txt
head_lines=$(wc -l <"$summary")
summarize() {
  python3 - "$csv" <<'PY' >"$table"
import csv, statistics, sys
rows = list(csv.DictReader(open(sys.argv[1])))
keys = sorted({(r["scene"], r["size"], r["spp"]) for r in rows}, key=lambda k: (k[1], k[0]))
print("scene size spp | variant: median ms total / primary / resolve / bounce (of it: clustering + views + shading, the clustering on the GPU for gl and gl-compute; GPU time of the resident bounce and, for gl-compute, resolve), PSNR against embree | bounce gl-readback / gl")
for key in keys:
    line, bounce = [], {}
    for variant in ("embree", "gl", "gl-compute", "gl-readback"):
        rs = [r for r in rows if (r["scene"], r["size"], r["spp"]) == key and r["variant"] == variant]
        if not rs:
            continue
        med = lambda f: statistics.median(float(r[f]) for r in rs)
        bounce[variant] = med("ms_bounce")
        gpu = [float(r["gpu_bounce_layers"]) + float(r["gpu_bounce_trace"]) + float(r["gpu_bounce_clustering"] or 0) +
               float(r["gpu_primary_resolve"] or 0) for r in rs if r["gpu_bounce_layers"]]
        host = [sum(float(r[k]) for k in ("host_clustering", "host_views", "host_shading")) for r in rs
                if r["host_clustering"]]
        psnr = rs[-1]["psnr_db"]
        notes = ", ".join((["host %.0f" % statistics.median(host)] if host else []) +
                          (["GPU %.1f" % statistics.median(gpu)] if gpu else []))
        line.append(("%s %.0f / %.0f / %.0f / %.0f%s %s" % (variant, med("ms_total"), med("ms_primary"),
                                                          med("ms_resolve"), med("ms_bounce"),
                                                          " (%s)" % notes if notes else "",
                                                          psnr + " dB" if psnr not in ("", "-") else "")).strip())
    ratio = "%.2fx" % (bounce["gl-readback"] / bounce["gl"]) if bounce.get("gl") and "gl-readback" in bounce else "-"
    print("%s %s %s | %s | %s" % (key[0], key[1], key[2], "; ".join(line), ratio))
PY
  { head -n "$head_lines" "$summary"; cat "$table"; } >"$work/summary.new" && mv "$work/summary.new" "$summary"
}
for scene in mirror-sphere water curved-mirror mirror-motion; do
  scene_runs "$scene" "$size" "$spp"
  summarize
done
if [ "$kind" = hardware ]; then
  scene_runs water 800x600 100
  summarize
fi
cat "$table"
[ "$kind" = hardware ] && say "JCST (water, 800x600, 100 spp): the paper's 196 ms on a GTX 285 (Xie et al. 2013)"
exit $((failed > 0))
