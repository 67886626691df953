# What bench/gpu/run.sh and bench/gpu/secondary.sh share, sourced by them:
# the blurcull binary, the output folder and summary, which GL the machine
# has, and the machine's lines of the summary. Set before sourcing: `script`
# (the caller's name, for messages) and `summary_name` (its summary file).
blurcull=$(command -v blurcull || true)
[ -n "$blurcull" ] || blurcull=build/frontend/blurcull
[ -x "$blurcull" ] || { echo "$script: no blurcull on PATH or in build/frontend" >&2; exit 2; }
dest=${OUT:-$PWD/gpu-bench}
mkdir -p "$dest"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
summary=$dest/$summary_name
: >"$summary"
say() { echo "$*" | tee -a "$summary"; }

# probe_gl ARGS...: a tiny gl render with ARGS names the GL (render --json's
# gl_renderer); sets `renderer` and `kind` (software: llvmpipe, softpipe,
# swrast; else hardware).
probe_gl() {
  local probe
  probe=$("$blurcull" render --backend gl "$@" --size 8x8 --spp 4 --json -q -o "$work/probe.png" 2>"$work/probe.err")
  renderer=$(printf '%s' "$probe" | python3 -c 'import json, sys; print(json.load(sys.stdin).get("gl_renderer", "?"))' \
             2>/dev/null || echo "none ($(head -c 200 "$work/probe.err"))")
  case "$renderer" in
    *llvmpipe*|*softpipe*|*swrast*) kind=software ;;
    *) kind=hardware ;;
  esac
}

# The date and the GPU (where nvidia-smi is) into the summary.
say_machine() {
  say "date: $(date -u +%FT%TZ)"
  command -v nvidia-smi >/dev/null && say "gpu: $(nvidia-smi --query-gpu=name,driver_version --format=csv,noheader 2>&1)"
  return 0
}
