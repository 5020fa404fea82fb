#!/usr/bin/env bash
# moyo plot vs vpype on the same synthetic plotter SVGs.
#
#   bench/vs_vpype.sh            # 10,000 and 100,000 random paths + 100,000 chain pieces
#   bench/vs_vpype.sh 2000       # custom sizes (each size: random and chains)
#
# Creates a Python virtual environment with vpype in target/vpype-venv when
# missing, generates the inputs (bench/gen_paths.py), runs
#   vpype read IN linemerge linesort write OUT
#   moyo  plot IN --merge --sort -o OUT
# and measures both outputs with the same independent script
# (bench/svg_metrics.py). Prints wall-time, peak-memory, pen-up-travel and
# ink ratios (vpype / moyo for time and memory: >1 means moyo is better;
# moyo / vpype for travel and ink). Results: target/bench/vs_vpype.md.
set -euo pipefail
# shellcheck source=bench/lib.sh
source "$(dirname "$0")/lib.sh"

venv=target/vpype-venv
if [ ! -x "$venv/bin/vpype" ]; then
  python3 -m venv "$venv"
  "$venv/bin/pip" install --quiet --disable-pip-version-check "vpype==1.15.0"
fi
cargo build --release --quiet --bin moyo
moyo=target/release/moyo

metric() { "$venv/bin/python" bench/svg_metrics.py "$1" | "$venv/bin/python" -c "import json,sys; print(json.load(sys.stdin)['$2'])"; }
ratio() { "$venv/bin/python" -c "print(f'{$1 / $2:.2f}' if $2 else 'inf')"; }

sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(10000 100000)
{
  echo "| input | paths | vpype s | moyo s | time ×| vpype MiB | moyo MiB | memory × | pen-up vpype mm | pen-up moyo mm | travel moyo/vpype | ink moyo/vpype |"
  echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
  for n in "${sizes[@]}"; do
    for kind in random chains; do
      [ "$kind" = chains ] && [ "$n" -lt 100000 ] && [ ${#@} -eq 0 ] && continue
      in="$work/$kind-$n.svg"
      python3 bench/gen_paths.py "$kind" "$n" "$in"
      read -r vt vm < <(measure "$venv/bin/vpype" read "$in" linemerge linesort write "$work/vpype.svg")
      read -r mt mm < <(measure "$moyo" plot "$in" --merge --sort -o "$work/moyo.svg")
      vu=$(metric "$work/vpype.svg" pen_up_mm); mu=$(metric "$work/moyo.svg" pen_up_mm)
      vi=$(metric "$work/vpype.svg" pen_down_mm); mi=$(metric "$work/moyo.svg" pen_down_mm)
      printf '| %s | %s | %s | %s | %s | %.0f | %.0f | %s | %.0f | %.0f | %s | %s |\n' \
        "$kind" "$n" "$vt" "$mt" "$(ratio "$vt" "$mt")" \
        "$(ratio "$vm" 1024)" "$(ratio "$mm" 1024)" "$(ratio "$vm" "$mm")" \
        "$vu" "$mu" "$(ratio "$mu" "$vu")" "$(ratio "$mi" "$vi")"
    done
  done
} | tee "$out/vs_vpype.md"
