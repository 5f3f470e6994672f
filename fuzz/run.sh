#!/usr/bin/env bash
# The fuzz targets (issues 11 and 21; CI: `bash fuzz/run.sh`).
#
#   bash fuzz/run.sh                   # CI: replay every kept input of every target:
#                                      # fuzz/regressions/<t>/ (crashes found and fixed)
#                                      # and fuzz/corpus/<t>.tar.gz (the committed corpus)
#   bash fuzz/run.sh TARGET...         # only these targets
#   FUZZ_EXPLORE=1 bash fuzz/run.sh    # and then fuzz each target from its corpus: a fixed
#                                      # number of executions from FUZZ_SEED (20211), or
#                                      # FUZZ_SECONDS=600 with a random seed (printed;
#                                      # FUZZ_SECONDS alone explores too)
#   FUZZ_GROW=1 bash fuzz/run.sh       # explore, then merge what found new coverage into
#                                      # fuzz/corpus/<t>.tar.gz (libFuzzer -merge=1; commit it)
#
# Why CI replays and does not explore: libFuzzer's path through the inputs depends on
# the binary itself (comparison values are hashed by code address), and the binary
# depends on the toolchain and on where the clone lies (cargo hashes a path
# dependency's location into its symbols). A fixed seed and run count gave the same
# inputs on one machine, but another clone found crashes this one did not: CI could
# fail on an unchanged tree. Replaying fixed files is the same everywhere; exploring
# is a developer's step, and what it finds is kept in fuzz/regressions/<t>/ and as a
# test in tests/stability/fuzz_regressions.rs, what it covers in fuzz/corpus/<t>.tar.gz (FUZZ_GROW;
# an archive per target: thousands of small inputs, about 1.4 MB in all).
#
# Builds the targets as `cargo fuzz build -s none` does (libFuzzer with
# SanitizerCoverage, no sanitizer: works on stable Rust; cargo-fuzz need not be
# installed here), with the workspace's `fuzz` profile (Cargo.toml at the root:
# opt-level 3, overflow checks and debug assertions on; the binaries land in the
# workspace's target/<host triple>/fuzz/). Any crash (a panic: overflow checks are
# on) fails loudly: exit 1, the crashing input in fuzz/artifacts/<target>/ when
# exploring, the libFuzzer log on stderr. Prints inputs, executions and time.
set -euo pipefail
shopt -s nullglob
cd "$(dirname "$0")"
# executions per target when exploring from the fixed seed (about 30 s each here)
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
export RUSTFLAGS=" -Cpasses=sancov-module -Cllvm-args=-sanitizer-coverage-level=4 -Cllvm-args=-sanitizer-coverage-inline-8bit-counters -Cllvm-args=-sanitizer-coverage-pc-table -Cllvm-args=-sanitizer-coverage-trace-compares --cfg fuzzing -Cllvm-args=-simplifycfg-branch-fold-threshold=0 -Cllvm-args=-sanitizer-coverage-stack-depth -Ccodegen-units=1"
cargo build --quiet --profile fuzz --target "$triple" --bins
target_dir="${CARGO_TARGET_DIR:-../target}"
status=0
for t in "${targets[@]}"; do
  bin="$target_dir/$triple/fuzz/$t"
  if [ -z "${RUNS[$t]:-}" ]; then
    echo "FAIL fuzz $t: no such target" >&2
    status=1
    continue
  fi
  mkdir -p corpus "artifacts/$t"
  unpacked="$(mktemp -d)"
  if [ -f "corpus/$t.tar.gz" ]; then
    tar -xzf "corpus/$t.tar.gz" -C "$unpacked"
  fi
  mkdir -p "$unpacked/$t"
  kept=(regressions/"$t"/* "$unpacked/$t"/*)
  log="$(mktemp)"
  start="$(date +%s)"
  # every kept input run once (libFuzzer runs file arguments one by one)
  if [ "${#kept[@]}" -gt 0 ] && ! "$bin" "${kept[@]}" >"$log" 2>&1; then
    grep -v '^ \+\(at \|[0-9]\+: \)' "$log" | tail -40 >&2
    echo "FAIL fuzz $t: a kept input of fuzz/regressions/$t or fuzz/corpus/$t.tar.gz crashes" >&2
    status=1
    rm -rf "$log" "$unpacked"
    continue
  fi
  echo "ok   fuzz $t: ${#kept[@]} kept inputs replayed in $(($(date +%s) - start)) s, no crash"
  if [ -z "${FUZZ_EXPLORE:-}${FUZZ_GROW:-}${secs}" ]; then
    rm -rf "$log" "$unpacked"
    continue
  fi
  work="$(mktemp -d)"
  if [ "${#kept[@]}" -gt 0 ]; then
    cp "${kept[@]}" "$work"/
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
  if "$bin" "${limit[@]}" -reload=0 -print_final_stats=1 -artifact_prefix="artifacts/$t/" "$work" >"$log" 2>&1; then
    n="$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")"
    echo "ok   fuzz $t: explored, $n executions ($what) in $(($(date +%s) - start)) s, no crash"
    if [ -n "${FUZZ_GROW:-}" ]; then
      before="$(ls "$unpacked/$t" | wc -l)"
      "$bin" -merge=1 "$unpacked/$t" "$work" >"$log" 2>&1
      # a reproducible archive: sorted names, no times or owners
      tar --sort=name --mtime=@0 --owner=0 --group=0 --numeric-owner -cf - -C "$unpacked" "$t" \
        | gzip -n -9 >"corpus/$t.tar.gz"
      echo "     fuzz $t: corpus/$t.tar.gz grew from $before to $(ls "$unpacked/$t" | wc -l) inputs"
    fi
  else
    grep -v '^ \+\(at \|[0-9]\+: \)' "$log" | tail -40 >&2
    echo "FAIL fuzz $t ($what): crash (input in fuzz/artifacts/$t/; keep it in fuzz/regressions/$t and as a test in tests/stability/fuzz_regressions.rs)" >&2
    status=1
  fi
  rm -rf "$work" "$log" "$unpacked"
done
exit "$status"
