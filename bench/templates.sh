#!/usr/bin/env bash
# Render time of every built-in template, SVG only and SVG + PNG (150 dpi),
# through the release CLI. Figures go to BENCHMARKS.md §6. Run from the
# crate root:   bench/templates.sh [RUNS]        (default 10 runs each)
# Needs hyperfine (apt-get install -y hyperfine).
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-10}
out=${BENCH_OUT:-target/bench}
mkdir -p "$out"
cargo build --release --bin moyo
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
moyo=target/release/moyo
args=()
for t in $("$moyo" templates | cut -f1 | awk '{print $1}'); do
  args+=(-n "$t svg" "$moyo render -t $t -o $tmp/$t.svg")
  args+=(-n "$t svg+png" "$moyo render -t $t -o $tmp/$t.svg --png $tmp/$t.png")
done
hyperfine --warmup 1 --runs "$runs" --style basic --export-markdown "$out/templates.md" "${args[@]}" >/dev/null
cat "$out/templates.md"
for t in $("$moyo" templates | cut -f1 | awk '{print $1}'); do
  "$moyo" render -t "$t" -o "$tmp/$t.svg" 2>&1 | sed "s/^/$t: /"
done
