#!/usr/bin/env bash
# Peak memory of `moyo plot IN --merge --sort` at the import limits
# (RELIABILITY.md, "Resource bounds").
#
#   bench/limits.sh
#
# Generates each input with bench/gen_paths.py, runs the plot in release
# and prints one markdown row per input: the file size, wall seconds and
# peak RSS from GNU time, and whether moyo plotted it or refused it (with
# its message). Results: target/bench/limits.md.
set -euo pipefail
# shellcheck source=bench/lib.sh
source "$(dirname "$0")/lib.sh"

cargo build --release --quiet --bin moyo
moyo=target/release/moyo

rows=(
  "random 999990|999,990 short cubic paths (\`gen_paths.py random 999990\`)"
  "random 1000000|1,000,000 paths (\`gen_paths.py random 1000000\`): one element too many"
  "lines 999990 10|999,990 paths of 10 line segments (\`gen_paths.py lines 999990 … 10\`): the heaviest within both limits"
  "lines 99 100000|99 paths of 100,000 line segments, 9.9 million (\`gen_paths.py lines 99 … 100000\`)"
  "lines 500000 21|500,000 paths of 21 segments, 10.5 million (\`gen_paths.py lines 500000 … 21\`): past the segment limit"
)

{
  echo "| input | file | time | peak memory | result |"
  echo "|---|---:|---:|---:|---|"
  for row in "${rows[@]}"; do
    read -r kind n k <<< "${row%%|*}"
    python3 bench/gen_paths.py "$kind" "$n" "$work/in.svg" ${k:+"$k"}
    mb=$(( $(stat -c %s "$work/in.svg") / 1000000 ))
    if /usr/bin/time -f "%e %M" -o "$work/time" \
        "$moyo" plot "$work/in.svg" --merge --sort -o "$work/out.svg" \
        > /dev/null 2> "$work/stderr"; then
      result=plotted
    else
      result="refused: $(grep -v '^$' "$work/stderr" | tail -1)"
    fi
    # GNU time puts "Command exited with non-zero status N" before its
    # figures when the command fails.
    read -r seconds kib < <(tail -1 "$work/time")
    gb=$(python3 -c "print(f'{$kib / 1048576:.2f}')")
    echo "| ${row#*|} | $mb MB | $seconds s | $gb GB | $result |"
    rm -f "$work/in.svg" "$work/out.svg"
  done
} | tee "$out/limits.md"
