#!/usr/bin/env bash
# Issue 23's bench: every built-in scene through the gl backend's compute and
# fragment pipelines, the cpu backend and embree, in one run, on whatever GL
# the machine has, with the compute pipeline's phases (GL timer queries:
# gpu_setup, gpu_binning, gpu_raster, gpu_resolve; and the host's clock over
# each, wall_*). docs/gl-backend.md, "The compute pipeline".
#
# Build and pack here, then run from the bundle on the device:
#   cmake --build build
#   bash ../shared/gpu/bundle.sh build blurcull
#   bash .gpu/env.sh bash bench/gpu/run.sh            (carry [".gpu"])
# It also runs here (llvmpipe, build/frontend/blurcull): there it is a smoke
# run, labelled software, at 128x96, 4 spp, one run each unless BENCH_SIZE,
# BENCH_SPP, BENCH_RUNS say otherwise. On a hardware GPU: 1024x768, 16 spp,
# 3 runs each (medians). BENCH_SCENES (default: hand car dragonfly forest)
# and BENCH_BACKENDS (default: compute compute-noocc fragment cpu embree)
# pick a subset; compute-noocc is the compute pipeline with --occlusion off,
# whose samples_hit counts every covered sample as the fragment pipeline's.
# Then the large runs, once each: BENCH_LARGE (on a hardware GPU every
# built-in scene at 1920x1080, 64 spp through compute, cpu and embree, and
# forest-10m at 1920x1080, 16 spp through compute: the issue's targets; on
# llvmpipe none), entries scene@size@spp[@runs@backend,backend...] (default
# 1 run, compute), with the frame's largest GPU buffer total
# (gpu_buffer_bytes) and its triangle batches.
# Writes bench.csv (one line per render) and summary.txt (medians) under
# $OUT (or ./gpu-bench when unset); exits non-zero if a render failed or, on
# llvmpipe, compute-noocc and fragment disagree on a scene's samples_hit.
set -u
script=run.sh
summary_name=summary.txt
# shellcheck source=bench/gpu/bench_common.sh
. "$(dirname "$0")/bench_common.sh"
csv=$dest/bench.csv

# What GL is this? A tiny compute render names it.
probe_gl --gl-pipeline compute --scene hand
if [ "$kind" = software ]; then def_size=128x96; def_spp=4; def_runs=1; else def_size=1024x768; def_spp=16; def_runs=3; fi
size=${BENCH_SIZE:-$def_size}
spp=${BENCH_SPP:-$def_spp}
runs=${BENCH_RUNS:-$def_runs}
scenes=${BENCH_SCENES:-"hand car dragonfly forest"}
backends=${BENCH_BACKENDS:-"compute compute-noocc fragment cpu embree"}
if [ "$kind" = software ]; then
  def_large=""
else
  def_large=""
  for scene in hand car dragonfly forest; do def_large="$def_large $scene@1920x1080@64@1@compute,cpu,embree"; done
  def_large="$def_large forest-10m@1920x1080@16"
fi
large=${BENCH_LARGE-$def_large}
say_machine
say "gl: $renderer ($kind)"
say "cpus: $(nproc); size $size, spp $spp, runs $runs, cull bbox, seed 1, sampler sobol"
[ "$kind" = software ] && say "SOFTWARE GL (llvmpipe on the CPU): a smoke run, not GPU figures"

echo "scene,backend,run,frame_ms,compile_ms,samples_hit,samples_tested,gpu_setup,gpu_binning,gpu_raster,gpu_resolve,wall_setup,wall_binning,wall_raster,wall_resolve,tile_list_entries,tile_list_longest,gpu_buffer_bytes,triangle_batches,size,spp" >"$csv"
failed=0
# The main runs (every backend at $size, $spp, $runs times), then the scale
# runs (compute, once): entries scene@size@spp.
entries=""
for scene in $scenes; do entries="$entries $scene@$size@$spp@$runs@$(echo "$backends" | tr ' ' ,)"; done
for item in $large; do
  case "$item" in *@*@*@*@*) entries="$entries $item" ;; *) entries="$entries $item@1@compute" ;; esac
done
for entry in $entries; do
  IFS=@ read -r scene size_here spp_here runs_here backends_here <<<"$entry"
  for backend in ${backends_here//,/ }; do
    case "$backend" in
      compute) args="--backend gl --gl-pipeline compute" ;;
      compute-noocc) args="--backend gl --gl-pipeline compute --occlusion off" ;;
      fragment) args="--backend gl --gl-pipeline fragment" ;;
      *) args="--backend $backend" ;;
    esac
    for run in $(seq 1 "$runs_here"); do
      # shellcheck disable=SC2086
      if ! "$blurcull" render $args --scene "$scene" --size "$size_here" --spp "$spp_here" --json -q \
           -o "$work/$scene-$backend.png" >"$work/out.json" 2>"$work/err.txt"; then
        say "$scene $backend: FAILED: $(head -c 300 "$work/err.txt")"
        failed=$((failed + 1))
        break
      fi
      python3 - "$scene" "$backend" "$run" "$work/out.json" "$size_here" "$spp_here" >>"$csv" <<'PY'
import json, sys
scene, backend, run, path, size, spp = sys.argv[1:7]
d = json.load(open(path))
p = d.get("ms_per_phase", {})
c = d.get("counters", {})
compile_ms = p.get("compile", 0.0)
row = [scene, backend, run, "%.1f" % (d["ms_total"] - compile_ms), "%.1f" % compile_ms,
       str(d["samples_hit"]), str(d["samples_tested"])]
row += ["%.2f" % p[k] if k in p else "" for k in
        ("gpu_setup", "gpu_binning", "gpu_raster", "gpu_resolve", "wall_setup", "wall_binning", "wall_raster",
         "wall_resolve")]
row += ["%d" % c[k] if k in c else "" for k in ("tile_list_entries", "tile_list_longest", "gpu_buffer_bytes",
                                              "triangle_batches")]
print(",".join(row + [size, spp]))
PY
    done
  done
done

# Medians per scene and backend; the compute and fragment pipelines must
# count the same hits (the same samples decided the same way).
python3 - "$csv" "$kind" >"$work/table.txt" <<'PY' || failed=$((failed + 1))
import csv, statistics, sys
rows = list(csv.DictReader(open(sys.argv[1])))
kind = sys.argv[2]
def med(values):
    values = [float(v) for v in values if v != ""]
    return statistics.median(values) if values else float("nan")
print("\nframe ms (render minus shader compile), median; compute phases in ms (gpu: timer queries, wall: host clock)"
      + (" -- SOFTWARE GL" if kind == "software" else ""))
print("%-26s %-14s %10s %10s  %s" % ("scene", "backend", "frame_ms", "hits", "compute phases gpu setup/binning/raster/resolve | wall"))
bad = 0
for key in dict.fromkeys((r["scene"], r["size"], r["spp"]) for r in rows):
    scene = "%s %s %sspp" % key
    hits = {}
    for backend in dict.fromkeys(r["backend"] for r in rows if (r["scene"], r["size"], r["spp"]) == key):
        rs = [r for r in rows if (r["scene"], r["size"], r["spp"]) == key and r["backend"] == backend]
        hits[backend] = rs[0]["samples_hit"]
        phases = ""
        if backend.startswith("compute"):
            phases = "/".join("%.1f" % med(r[k] for r in rs) for k in ("gpu_setup", "gpu_binning", "gpu_raster", "gpu_resolve"))
            phases += " | " + "/".join("%.1f" % med(r[k] for r in rs) for k in ("wall_setup", "wall_binning", "wall_raster", "wall_resolve"))
            phases += " | %.0f MiB, %s batches" % (med(r["gpu_buffer_bytes"] for r in rs) / 2**20, rs[0]["triangle_batches"])
        print("%-26s %-14s %10.1f %10s  %s" % (scene, backend, med(r["frame_ms"] for r in rs), hits[backend], phases))
    # Every backend against the compute pipeline, frame time for frame time,
    # and the compute pipeline's GPU time (timer queries, setup to resolve).
    frames = {b: med(r["frame_ms"] for r in rows if (r["scene"], r["size"], r["spp"]) == key and r["backend"] == b)
              for b in hits}
    if "compute" in frames:
        rs = [r for r in rows if (r["scene"], r["size"], r["spp"]) == key and r["backend"] == "compute"]
        gpu = sum(med(r[k] for r in rs) for k in ("gpu_setup", "gpu_binning", "gpu_raster", "gpu_resolve"))
        others = ", ".join("%s/compute %.2f" % (b, frames[b] / frames["compute"]) for b in frames
                           if b != "compute" and frames["compute"] > 0)
        print("%-26s compute GPU time %.2f ms%s" % ("", gpu, ("; " + others) if others else ""))
    if "compute-noocc" in hits and "fragment" in hits and hits["compute-noocc"] != hits["fragment"]:
        # llvmpipe is IEEE-exact, so there they must agree; a GPU may
        # compile the same GLSL differently in two shaders (../shared/gpu/README.md).
        print("  %s: compute (occlusion off) and fragment hits differ (%s, %s)%s" % (scene, hits["compute-noocc"], hits["fragment"],
              "" if kind == "software" else ": reported, not a failure off llvmpipe"))
        bad += kind == "software"
sys.exit(1 if bad else 0)
PY
tee -a "$summary" <"$work/table.txt"
say "failed: $failed"
[ "$failed" -eq 0 ]
