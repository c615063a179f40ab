#!/usr/bin/env bash
# Runs libFuzzer targets for a bounded time each: `make fuzz` calls it.
#   fuzz/run.sh BUILD_DIR SECONDS TARGET...
# Each target starts from fuzz/corpus/<target>, copied into
# BUILD_DIR/corpus/<target> so that the inputs it finds do not change the
# repository (add the useful ones by hand: see docs/config.md, "Fuzzing").
# A crash, a violated invariant, a leak or a timeout fails the run; the
# input is saved as BUILD_DIR/artifacts/<target>-crash-... and the report
# is printed. Exit 0 when every target ran clean.
set -euo pipefail
build=$1 seconds=$2
shift 2
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$build/artifacts" "$build/logs"
status=0
for t in "$@"; do
  corpus=$build/corpus/$t
  mkdir -p "$corpus"
  cp -n "$here/corpus/$t/"* "$corpus/" 2>/dev/null || true
  log=$build/logs/$t.log
  # -close_fd_mask=3: the targets' own output (error messages of rejected
  # inputs, a million lines a minute) is dropped; libFuzzer's and the
  # sanitizers' reports still reach the log. -timeout: no input may take
  # longer (the slowest legitimate ones take well under a second).
  if "$build/fuzz/fuzz_$t" -max_total_time="$seconds" -timeout=20 -rss_limit_mb=2048 -close_fd_mask=3 \
      -print_final_stats=1 -artifact_prefix="$build/artifacts/$t-" "$corpus" >"$log" 2>&1; then
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
    echo "fuzz $t: ${runs:-?} executions in ${seconds} s, no crash (corpus $(ls "$corpus" | wc -l) inputs)"
  else
    echo "fuzz $t: FAILED; the end of $log:" >&2
    tail -n 40 "$log" >&2
    status=1
  fi
done
exit $status
