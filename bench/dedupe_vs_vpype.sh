#!/usr/bin/env bash
# moyo plot --dedupe vs vpype's deduplicate plug-in on the same synthetic
# plotter SVGs.
#
#   bench/dedupe_vs_vpype.sh              # 100,000 and 1,000,000 segments
#   bench/dedupe_vs_vpype.sh 20000 50000  # custom sizes
#
# Creates a Python virtual environment with vpype in target/vpype-venv when
# missing and installs the plug-in into it (PyPI package `deduplicate`,
# which adds the `deduplicate` command), generates the inputs
# (`bench/gen_paths.py doubled N`: paths of 10 line segments on A3 in one
# pen layer, a fifth of them drawn again over an earlier one, exactly,
# reversed, shifted along it or moved 0.02 mm), runs
#   moyo  plot IN -o OUT --dedupe TOL               (best of MOYO_RUNS runs)
#   vpype read IN deduplicate -t TOLmm write OUT    (once, cut at VPYPE_CAP s)
# with the same tolerance, and measures the input and both outputs with the
# same independent script (bench/pen_metrics.py): pen-down length, and the
# share of it lying on other line work within 0.075 mm (a quarter of the
# 0.3 mm pen). Results: target/bench/dedupe_vs_vpype.md.
#
# Environment: MOYO (the binary to time; by default this builds
# target/release/moyo), DEDUPE_TOL (mm, default 0.075), VPYPE_CAP (s, default
# 900), MOYO_RUNS (default 3), SEGMENT_MM (mean segment length, default 0.4:
# a million segments then ink the A3 sheet about once over at 0.3 mm).
set -euo pipefail
# shellcheck source=bench/lib.sh
source "$(dirname "$0")/lib.sh"

tol=${DEDUPE_TOL:-0.075}
cap=${VPYPE_CAP:-900}
runs=${MOYO_RUNS:-3}
seg_mm=${SEGMENT_MM:-0.4}

venv=target/vpype-venv
[ -x "$venv/bin/vpype" ] || python3 -m venv "$venv"
if ! "$venv/bin/vpype" deduplicate --help > /dev/null 2>&1; then
  # deduplicate 0.1.0 (2022) is the plug-in's only release; it needs vpype
  # >= 1.9, < 2 and works with 1.15.
  "$venv/bin/pip" install --quiet --disable-pip-version-check "vpype==1.15.0" "deduplicate==0.1.0"
fi
if [ -n "${MOYO:-}" ]; then
  moyo=$MOYO
else
  cargo build --release --quiet --bin moyo
  moyo=target/release/moyo
fi

mb() { "$venv/bin/python" -c "print(f'{$1 * 1024 / 1e6:.0f}')"; }
# Pen-down mm and doubled % of a file (bench/pen_metrics.py, totals).
metrics() {
  "$venv/bin/python" bench/pen_metrics.py --json "$1" | "$venv/bin/python" -c \
    "import json,sys; t=json.load(sys.stdin)['total']; print(f\"{t['pen_down_mm']:.0f} {t['doubled_pct']:.1f}\")"
}

sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(100000 1000000)
started=$SECONDS
{
  echo "| input | segments | moyo s | moyo MB | vpype s | vpype MB | length before mm | moyo length after mm | vpype length after mm | doubled before % | moyo doubled after % | vpype doubled after % |"
  echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
  for n in "${sizes[@]}"; do
    in="$work/doubled-$n.svg"
    python3 bench/gen_paths.py doubled "$n" "$in" "$seg_mm"

    echo "$n segments: moyo ($runs runs)" >&2
    mt='' mm=''
    for _ in $(seq "$runs"); do
      r=$(measure "$moyo" plot "$in" -o "$work/moyo.svg" --dedupe "$tol")
      read -r t m <<< "$r"
      if [ -z "$mt" ] || "$venv/bin/python" -c "import sys; sys.exit(not $t < $mt)"; then
        mt=$t mm=$m
      fi
    done

    echo "$n segments: vpype (at most $cap s)" >&2
    rm -f "$work/vpype.svg"
    rc=0
    /usr/bin/time -f "%e %M" -o "$work/time" timeout "$cap" \
      "$venv/bin/vpype" read "$in" deduplicate -t "${tol}mm" write "$work/vpype.svg" \
      > /dev/null 2> "$work/stderr" || rc=$?
    read -r vt vm < <(tail -1 "$work/time")
    if [ "$rc" = 124 ]; then
      vt="> $cap" vmb="≥ $(mb "$vm")"
    elif [ "$rc" != 0 ]; then
      cat "$work/stderr" >&2
      exit 1
    else
      vmb=$(mb "$vm")
    fi

    echo "$n segments: measuring" >&2
    r=$(metrics "$in") && read -r len0 dbl0 <<< "$r"
    r=$(metrics "$work/moyo.svg") && read -r len_m dbl_m <<< "$r"
    if [ "$rc" = 0 ]; then
      r=$(metrics "$work/vpype.svg") && read -r len_v dbl_v <<< "$r"
    else
      len_v="–" dbl_v="–"
    fi
    printf '| doubled %s mm | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n' \
      "$seg_mm" "$n" "$mt" "$(mb "$mm")" "$vt" "$vmb" "$len0" "$len_m" "$len_v" \
      "$dbl0" "$dbl_m" "$dbl_v"
  done
  echo
  echo "Tolerance $tol mm for both (moyo \`--dedupe $tol\`, vpype \`deduplicate -t ${tol}mm\`;" \
    "the plug-in's default is 0.01 mm). moyo: best of $runs runs; vpype: one run, cut at $cap s." \
    "MB: peak resident memory (GNU time), 10⁶ bytes. Lengths and doubled %: bench/pen_metrics.py" \
    "(doubled: lying on earlier line work of the pen within 0.075 mm)." \
    "Run took $((SECONDS - started)) s."
} | tee "$out/dedupe_vs_vpype.md"
