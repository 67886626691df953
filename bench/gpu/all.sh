#!/usr/bin/env bash
# Every prepared GPU run in one command, for a session lent a GPU machine
# (about 15 minutes of device time, start included; at most 10 minutes a
# command): issue 22's correctness check (check.sh) and exit check
# (exit_check.sh), issue 23's bench (run.sh) and issue 24's (secondary.sh),
# each under a time budget, in the issues' order of work. Writes
# summary.txt (every part's summary, in turn) and all.tar.gz (every part's
# files) under $OUT (or ./gpu-all): two files, within what a device run
# brings back.
#
#   cmake --build build
#   bash ../shared/gpu/bundle.sh build $(bash bench/gpu/all.sh --list)
#   bash .gpu/env.sh bash bench/gpu/all.sh      (carry [".gpu"], timeout_s 600)
#
# GPU_ALL_BUDGETS="check exit run secondary" in seconds (default "265 45
# 160 90": 560 s in all; run.sh's 1920x1080 renders take ~60 s of it) and GPU_ALL_PARTS (default "check exit run
# secondary") change what runs; here (llvmpipe) e.g.
#   GPU_ALL_PARTS="exit secondary" GPU_ALL_BUDGETS="0 60 0 120" bash bench/gpu/all.sh
set -u
here=$(cd "$(dirname "$0")" && pwd)
if [ "${1:-}" = "--list" ]; then
  # check.sh's executables hold exit_check.sh's, run.sh's and secondary.sh's (blurcull).
  bash "$here/check.sh" --list
  exit 0
fi
dest=${OUT:-$PWD/gpu-all}
mkdir -p "$dest"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
summary=$dest/summary.txt
: >"$summary"
read -r -a budget <<<"${GPU_ALL_BUDGETS:-265 45 160 90}"
# One render per variant in the benches (their medians want 3: BENCH_RUNS=3
# where the budget allows).
export BENCH_RUNS=${BENCH_RUNS:-1}
parts=${GPU_ALL_PARTS:-"check exit run secondary"}
status=0
# part name, budget, script: runs it with OUT at its own folder, appends its summary.
part() {
  local name=$1 seconds=$2 script=$3 summary_file=$4
  case " $parts " in *" $name "*) ;; *) return ;; esac
  mkdir -p "$work/$name"
  echo "== $name ($script, budget ${seconds}s)" | tee -a "$summary"
  local start=$SECONDS
  OUT="$work/$name" timeout --kill-after=10 "$seconds" bash "$here/$script" >"$work/$name/stdout.txt" 2>&1
  local rc=$?
  [ -f "$work/$name/$summary_file" ] && cat "$work/$name/$summary_file" >>"$summary"
  echo "== $name: exit $rc in $((SECONDS - start))s$([ "$rc" -eq 124 ] && echo ' (budget spent: cut off)')" |
    tee -a "$summary"
  [ "$rc" -eq 0 ] || status=1
}
part check "${budget[0]:-265}" check.sh summary.txt
part exit "${budget[1]:-45}" exit_check.sh exit_check.txt
part run "${budget[2]:-160}" run.sh summary.txt
part secondary "${budget[3]:-90}" secondary.sh secondary-summary.txt
tar -C "$work" -czf "$dest/all.tar.gz" . 2>/dev/null
exit $status
