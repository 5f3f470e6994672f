#!/usr/bin/env bash
# The fuzz targets, deterministic (issues 11 and 21; CI: `bash fuzz/run.sh`).
#
#   bash fuzz/run.sh                     # CI: every target, a fixed seed and a fixed
#                                        # number of runs (the same inputs every time)
#   bash fuzz/run.sh TARGET...           # only these targets
#   FUZZ_SECONDS=600 bash fuzz/run.sh    # longer, exploring: a random seed per target
#                                        # (printed) and a wall-clock limit per target
#   FUZZ_SEED=123 bash fuzz/run.sh       # the fixed runs from another seed
#
# Builds the targets exactly as `cargo fuzz build -s none` does (libFuzzer with
# SanitizerCoverage, no sanitizer: works on stable Rust; cargo-fuzz need not be
# installed here; the same flags as cargo fuzz's, plus the source paths
# remapped, see below), replays every kept input of fuzz/regressions/<target>/, then
# fuzzes each target from those inputs: by default `-runs=N` executions from
# `-seed=S` (N per target below, about 30 s each on the 2-core CI machine) with
# `-reload=0` (libFuzzer otherwise rereads its corpus directory once a second,
# which makes the run depend on timing): the same inputs on every run of the
# same tree and toolchain, so CI fails only on a changed tree. Any crash (a panic: overflow checks are on in the
# fuzz profile) fails loudly: exit 1, the crashing input in
# fuzz/artifacts/<target>/, the libFuzzer log on stderr; keep the input in
# fuzz/regressions/<target>/ and as a test in tests/fuzz_regressions.rs.
# Prints the executions and the time per target.
set -euo pipefail
shopt -s nullglob
cd "$(dirname "$0")"
# executions per target in the fixed runs (about 30 s each here)
declare -A RUNS=(
  [lighting]=4000000
  [raster]=1000000
  [constructors]=5000000
  [mesh]=1000000
  [surface]=130000
)
seed="${FUZZ_SEED:-20211}"
secs="${FUZZ_SECONDS:-}"
targets=("$@")
if [ "${#targets[@]}" -eq 0 ]; then
  targets=(lighting raster constructors mesh surface)
fi
triple="$(rustc -vV | sed -n 's/^host: //p')"
# The source paths of the crate and of its dependencies are remapped to fixed
# names: panic locations and file names are compiled into the binary, and the
# fuzzer's path through the inputs depends on the binary, so a clone anywhere
# (CI clones elsewhere) builds the same binary and runs the same inputs.
repo="$(cd .. && pwd)"
cargo_home="${CARGO_HOME:-$HOME/.cargo}"
remap="--remap-path-prefix=$repo=/fixshade --remap-path-prefix=$cargo_home=/cargo"
export RUSTFLAGS="$remap -Cpasses=sancov-module -Cllvm-args=-sanitizer-coverage-level=4 -Cllvm-args=-sanitizer-coverage-inline-8bit-counters -Cllvm-args=-sanitizer-coverage-pc-table -Cllvm-args=-sanitizer-coverage-trace-compares --cfg fuzzing -Cllvm-args=-simplifycfg-branch-fold-threshold=0 -Cllvm-args=-sanitizer-coverage-stack-depth -Ccodegen-units=1"
cargo build --quiet --release --target "$triple" --bins
status=0
for t in "${targets[@]}"; do
  bin="target/$triple/release/$t"
  if [ -z "${RUNS[$t]:-}" ]; then
    echo "FAIL fuzz $t: no such target" >&2
    status=1
    continue
  fi
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
  if [ -n "$secs" ]; then
    s="$(od -An -N4 -tu4 /dev/urandom | tr -d ' ')"
    limit=(-max_total_time="$secs" -seed="$s")
    what="random seed $s, $secs s"
  else
    limit=(-runs="${RUNS[$t]}" -seed="$seed")
    what="seed $seed"
  fi
  start="$(date +%s)"
  if "$bin" "${limit[@]}" -reload=0 -print_final_stats=1 -artifact_prefix="artifacts/$t/" "$corpus" >"$log" 2>&1; then
    n="$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")"
    echo "ok   fuzz $t: ${#kept[@]} kept inputs replayed, $n executions ($what) in $(($(date +%s) - start)) s, no crash"
  else
    grep -v '^ \+\(at \|[0-9]\+: \)' "$log" | tail -40 >&2
    echo "FAIL fuzz $t ($what): crash (input in fuzz/artifacts/$t/; keep it in fuzz/regressions/$t and as a test in tests/fuzz_regressions.rs)" >&2
    status=1
  fi
  rm -rf "$corpus" "$log"
done
exit "$status"
