#!/usr/bin/env bash
# The GPU-correctness check (issue 22) in one run: every GL test executable,
# the GPU-side property test at full size, and the golden gl renders, on
# whatever GL the machine has. Runs from a bundle made by
# ../shared/gpu/bundle.sh (docs/glsl.md, "Checking on a GPU"):
#
#   cmake --build build
#   bash ../shared/gpu/bundle.sh build $(bash bench/gpu/check.sh --list)
#   bash .gpu/env.sh bash bench/gpu/check.sh          # on the GPU machine
#
# It also runs here (llvmpipe), which is how it is tested before a GPU run.
# Writes summary.txt and logs.tar.gz (a log per test) under $OUT (or
# ./gpu-check when unset). A test that dies on a signal is run again under cuda-gdb or gdb,
# where one is installed, for a backtrace.
set -u
gl_tests=(
  test_frontend_gl_parity test_frontend_gl_raster_parity test_frontend_gl_optics_parity
  test_frontend_gl_secondary_parity test_frontend_gl_dof_secondary test_frontend_gl_render test_frontend_gl_compute
  test_frontend_gl_methods test_frontend_shading test_frontend_sampler
  test_frontend_gl_arithmetic test_frontend_gl_properties test_frontend_gl_contexts
)
# GPU_CHECK_TESTS="a b" runs only those (to try the script itself).
[ -n "${GPU_CHECK_TESTS:-}" ] && read -r -a gl_tests <<<"$GPU_CHECK_TESTS"
if [ "${1:-}" = "--list" ]; then echo blurcull "${gl_tests[@]}"; exit 0; fi

dest=${OUT:-$PWD/gpu-check}
out=$(mktemp -d)
mkdir -p "$dest"
summary=$dest/summary.txt
: >"$summary"
say() { echo "$*" | tee -a "$summary"; }
# 10^7 covered samples per method on a GPU (the issue's figure); the test's
# default (200,000 x BLURCULL_PROPERTY_SCALE) stays small for llvmpipe.
export BLURCULL_GPU_PROPERTY_SAMPLES=${BLURCULL_GPU_PROPERTY_SAMPLES:-10000000}
export CI=true   # a missing GL context fails instead of skipping

say "date: $(date -u +%FT%TZ)"
command -v nvidia-smi >/dev/null && say "gpu: $(nvidia-smi --query-gpu=name,driver_version --format=csv,noheader 2>&1)"
say "cpus: $(nproc)"

# The command's compiled-in path, linked to the bundle's where it is missing.
# shellcheck source=bench/gpu/compiled_cli.sh
. "$(dirname "$0")/compiled_cli.sh"
for t in "${gl_tests[@]}"; do link_compiled_cli "$(command -v "$t" || true)"; done >>"$summary"

debugger=$(command -v cuda-gdb || command -v gdb || true)
failed=0
for t in "${gl_tests[@]}"; do
  exe=$(command -v "$t" || true)
  if [ -z "$exe" ]; then say "$t: MISSING (not in the bundle)"; failed=$((failed + 1)); continue; fi
  start=$(date +%s.%N)
  timeout 300 "$exe" >"$out/$t.log" 2>&1
  rc=$?
  secs=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }')
  summary_line=$(grep -E '^\[doctest\] (test cases|assertions):' "$out/$t.log" | tr -s ' ' | tr '\n' ' ')
  say "$t: exit $rc in ${secs}s; $summary_line"
  [ "$rc" -eq 0 ] || failed=$((failed + 1))
  if [ "$rc" -gt 128 ] && [ "$rc" -ne 124 ] && [ -n "$debugger" ]; then
    timeout 300 "$debugger" -batch -ex run -ex bt -ex 'info sharedlibrary' --args "$exe" --no-breaks=true \
      >"$out/$t.backtrace" 2>&1
    say "  backtrace: $(grep -m 3 -E '^#[0-9]' "$out/$t.backtrace" | tr '\n' ' ')"
  fi
done

# What the GPU-side property test counted (its MESSAGE lines).
grep -h -E 'false culls|covered' "$out/test_frontend_gl_properties.log" 2>/dev/null | head -40 >>"$summary"
# What the whole-render comparisons explained (tests/gl_render_reference.hpp:
# samples near an edge, depth ties, outside the model), on a GPU that is not
# IEEE-exact.
grep -h -E 'GL arithmetic|tolerant:' "$out/test_frontend_gl_render.log" "$out/test_frontend_sampler.log" 2>/dev/null |
  head -60 >>"$summary"

# The golden gl renders (tests/golden/golden_renders.cmake): exact PNG
# hashes and hit counts, recorded on llvmpipe, so off llvmpipe they are
# expected to differ at edges (issue 22); reported, not counted as a
# failure, until the golden script has a GPU tolerance.
golden=tests/golden/golden_renders.cmake
if [ -z "${GPU_CHECK_TESTS:-}" ] && command -v cmake >/dev/null && [ -f "$golden" ]; then
  timeout 600 cmake -DBLURCULL="$(command -v blurcull)" -DEXPECTED=tests/golden/golden_renders.txt \
    -DWORK_DIR="$out/golden" -DBACKENDS=gl -P "$golden" >"$out/golden_gl.log" 2>&1
  rc=$?
  say "golden_renders_gl (reported): exit $rc; $(grep -c "got '" "$out/golden_gl.log") renders differ; $(tail -n 2 "$out/golden_gl.log" | tr '\n' ' ')"
  rm -rf "$out/golden"
fi
say "failed: $failed"
# Two files come back: summary.txt and every log in one archive.
tar -czf "$dest/logs.tar.gz" -C "$out" .
rm -rf "$out"
[ "$failed" -eq 0 ]
