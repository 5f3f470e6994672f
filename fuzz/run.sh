#!/usr/bin/env bash
# The fuzz targets, bounded (issue 11; CI: `bash fuzz/run.sh 60`).
#
#   bash fuzz/run.sh [SECONDS]      # default 60 seconds per target
#
# Builds the targets exactly as `cargo fuzz build -s none` does (libFuzzer with
# SanitizerCoverage, no sanitizer: works on stable Rust; the same RUSTFLAGS, so
# `cargo fuzz run -s none <target>` reuses the build and cargo-fuzz need not be
# installed here), replays every kept input of fuzz/regressions/<target>/, then
# runs each target for SECONDS from those inputs. Any crash (a panic: overflow
# checks are on in the fuzz profile) fails loudly: exit 1, the crashing input in
# fuzz/artifacts/<target>/, the libFuzzer log on stderr. Prints the executions
# per target.
set -euo pipefail
shopt -s nullglob
cd "$(dirname "$0")"
secs="${1:-60}"
triple="$(rustc -vV | sed -n 's/^host: //p')"
export RUSTFLAGS=" -Cpasses=sancov-module -Cllvm-args=-sanitizer-coverage-level=4 -Cllvm-args=-sanitizer-coverage-inline-8bit-counters -Cllvm-args=-sanitizer-coverage-pc-table -Cllvm-args=-sanitizer-coverage-trace-compares --cfg fuzzing -Cllvm-args=-simplifycfg-branch-fold-threshold=0 -Cllvm-args=-sanitizer-coverage-stack-depth -Ccodegen-units=1"
cargo build --quiet --release --target "$triple" --bins
status=0
for t in lighting raster constructors; do
  bin="target/$triple/release/$t"
  kept=(regressions/"$t"/*)
  corpus="$(mktemp -d)"
  log="$(mktemp)"
  mkdir -p "artifacts/$t"
  if [ "${#kept[@]}" -gt 0 ]; then
    if ! "$bin" "${kept[@]}" >"$log" 2>&1; then
      cat "$log" >&2
      echo "FAIL fuzz $t: a kept input of fuzz/regressions/$t crashes again" >&2
      status=1
      continue
    fi
    cp "${kept[@]}" "$corpus"/
  fi
  if "$bin" -max_total_time="$secs" -print_final_stats=1 -artifact_prefix="artifacts/$t/" "$corpus" >"$log" 2>&1; then
    n="$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")"
    echo "ok   fuzz $t: ${#kept[@]} kept inputs replayed, $n executions in ${secs} s, no crash"
  else
    grep -v '^ \+\(at \|[0-9]\+: \)' "$log" | tail -40 >&2
    echo "FAIL fuzz $t: crash (input in fuzz/artifacts/$t/; keep it in fuzz/regressions/$t and as a test in tests/)" >&2
    status=1
  fi
  rm -rf "$corpus" "$log"
done
exit "$status"
