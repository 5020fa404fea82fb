#!/usr/bin/env bash
# Confirms where the per-tree override cost comes from: one set of N = 10,000
# small trees with K overrides (tree-0 … tree-(K-1)), timed through the CLI.
# If a tree's override is found by a linear search of the override list,
# extra time grows with the number of string comparisons
#   C(K) = 2 · (K(K+1)/2 + (N − K) · K)   (two lookups per tree)
# rather than with K. Run from the crate root: bench/overrides.sh
set -euo pipefail
cd "$(dirname "$0")/.."
out=${BENCH_OUT:-target/bench}
mkdir -p "$out"
cargo build --release --bin moyo
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
n=10000
cmds=()
for k in 0 1000 2500 5000 10000; do
  f="$tmp/k$k.toml"
  cat > "$f" <<TOML
version = 1
seed = 1
[page]
size = [4000, 1000]
orientation = "landscape"
margin = 10
[[layers]]
name = "row"
[layers.limbs]
style = "stroke"
[[layers.trees]]
id = "row"
rule = "tree2"
count = $n
centre = [[10, 900], [3970, 900]]
[layers.trees.params]
generations = 2
TOML
  for ((i = 0; i < k; i++)); do
    printf '[[layers.trees.overrides]]\nid = "tree-%d"\nscale = 1.0\n' "$i" >> "$f"
  done
  echo "K=$k: C(K) = $(( 2 * (k * (k + 1) / 2 + (n - k) * k) )) comparisons"
  cmds+=(-n "K=$k" "target/release/moyo render $f -o $tmp/k$k.svg")
done
hyperfine --warmup 1 --runs 10 --export-markdown "$out/overrides.md" "${cmds[@]}"
