#!/usr/bin/env bash
# Issue 22, item 4, on a GPU: do the GL test executables exit cleanly? Under
# NVIDIA's driver gl_render, gl_methods, shading and sampler died with SIGSEGV
# at exit (after their results) while a GlRenderer kept in a static was
# destroyed after the driver's exit handlers; test_frontend_gl_contexts makes,
# uses and destroys contexts with interleaved lifetimes and leaves one to the
# statics (docs/gl-backend.md, "Contexts"). Here a failed assertion and a crash
# are told apart: the status of each executable, "signal N" when it was killed.
#
# Build and pack here, then run from the bundle on the device:
#   bash ../shared/gpu/bundle.sh build test_frontend_gl_contexts test_frontend_gl_render \
#       test_frontend_gl_methods test_frontend_shading test_frontend_sampler
#   bash .gpu/env.sh bash bench/gpu/exit_check.sh        (carry [".gpu"])
# It also runs here (llvmpipe), with the executables on PATH or under build/tests.
# Writes exit_check.txt (and each executable's output) under $OUT when set.
set -u
out=${OUT:-$(mktemp -d)}
mkdir -p "$out"
tests=("$@")
[ ${#tests[@]} -gt 0 ] || tests=(test_frontend_gl_contexts test_frontend_gl_render test_frontend_gl_methods
                                 test_frontend_shading test_frontend_sampler)
summary="$out/exit_check.txt"
: > "$summary"
# shellcheck source=bench/gpu/compiled_cli.sh
. "$(dirname "$0")/compiled_cli.sh"
for t in "${tests[@]}"; do link_compiled_cli "$(command -v "$t" || true)"; done >>"$summary"
bad=0
for t in "${tests[@]}"; do
  exe=$(command -v "$t" || true)
  [ -n "$exe" ] || { [ -x "build/tests/$t" ] && exe="build/tests/$t"; }
  if [ -z "$exe" ]; then
    echo "$t: not found" | tee -a "$summary"; bad=1; continue
  fi
  start=$(date +%s)
  "$exe" > "$out/$t.log" 2>&1
  status=$?
  seconds=$(( $(date +%s) - start ))
  result=$(grep -E '^\[doctest\] (test cases|assertions)' "$out/$t.log" | tr -s ' ' | tr '\n' ' ')
  if [ $status -gt 128 ]; then
    what="signal $((status - 128)) ($(kill -l $((status - 128)) 2>/dev/null))"; bad=1
  else
    what="exit $status"; [ $status -eq 0 ] || bad=1
  fi
  echo "$t: $what, ${seconds} s; $result" | tee -a "$summary"
done
echo "$(grep -h -m1 -o 'GL: .*' "$out"/*.log 2>/dev/null | head -1)" | tee -a "$summary"
exit $bad
