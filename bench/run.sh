#!/usr/bin/env bash
# Reproduces every figure in BENCHMARKS.md. Run from the crate root:
#   bench/run.sh            # full run, results in target/bench/ (or $BENCH_OUT)
#   bench/run.sh --quick    # quicker library bench (3 runs, fewer counts)
# Needs hyperfine (apt-get install -y hyperfine) for the CLI timings; falls
# back to a shell loop with /usr/bin/time -v without it.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${BENCH_OUT:-target/bench}
mkdir -p "$out"

{
  echo "date: $(date -u +%Y-%m-%dT%H:%MZ)"
  echo "nproc: $(nproc)"
  grep -m1 'model name' /proc/cpuinfo
  echo "memory: $(awk '/MemTotal/ {printf "%.1f GiB", $2/1048576}' /proc/meminfo)"
  rustc --version
  echo "git: $(git rev-parse --short HEAD 2>/dev/null) ($(git status --short 2>/dev/null | wc -l) changed/untracked paths)"
  echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
} | tee "$out/machine.txt"

cargo build --release --bin moyo
cargo bench --bench bench --no-run

# 1. Library stages and scaling (median of N runs after warm-up).
cargo bench --quiet --bench bench -- "$@" | tee "$out/bench.md"

# 2. The whole CLI, default design, SVG only and SVG + PNG.
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
if command -v hyperfine >/dev/null; then
  hyperfine --warmup 3 --runs 20 --export-markdown "$out/cli.md" \
    -n 'render -o x.svg' "target/release/moyo render -t tomesode-hem -o $tmp/x.svg" \
    -n 'render -o x.svg --png x.png' "target/release/moyo render -t tomesode-hem -o $tmp/x.svg --png $tmp/x.png"
else
  for args in "-o $tmp/x.svg" "-o $tmp/x.svg --png $tmp/x.png"; do
    echo "moyo render $args: 20 runs"
    time (for _ in $(seq 20); do target/release/moyo render $args 2>/dev/null; done)
  done
fi

# Peak memory (maximum resident set size) of one run each.
for args in "-o $tmp/x.svg" "-o $tmp/x.svg --png $tmp/x.png"; do
  printf 'moyo render %s: ' "${args//$tmp\//}"
  /usr/bin/time -v target/release/moyo render $args 2>&1 >/dev/null \
    | awk -F': ' '/Maximum resident/ {m=$2} /Elapsed \(wall/ {w=$2} END {printf "max RSS %.1f MiB, wall %s\n", m/1024, w}'
done | tee "$out/memory.txt"

echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)" | tee -a "$out/machine.txt"
