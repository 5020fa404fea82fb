#!/usr/bin/env bash
# Pen-up tours against the limit (issue 33 item 1): moyo's sort against LKH
# and against vpype's `linesort --two-opt`, and its time on 100,000 paths.
#
#   bench/tour_vs_lkh.sh                     # everything, every template
#   bench/tour_vs_lkh.sh kimono-1 wagara     # only these templates
#   MOYO=path/to/moyo bench/tour_vs_lkh.sh   # another binary (else builds)
#
# Installs vpype 1.15.0 and elkai (LKH-3) into target/vpype-venv when
# missing. Travel is measured by bench/svg_metrics.py (svgelements, not
# moyo's code): the moves between consecutive subpaths, in file order.
#
# 1. 1,500 random segments on A3 (bench/tours.py segments, fixed seed):
#    `moyo plot IN --sort`, `vpype read IN linesort --two-opt write`, and
#    LKH's tour (bench/tours.py lkh: the model is described there).
# 2. Every template's largest plotted layer (by paths), alone and shuffled
#    (bench/tours.py largest), sorted by both tools from the same file.
# 3. 100,000 random paths (bench/gen_paths.py random): CPU seconds of
#    `moyo plot IN --sort` less those of `moyo plot IN` (reading and
#    writing), the best of three.
#
# Prints three ratios, moyo / LKH, the worst moyo / vpype over the
# templates, and the sort's seconds; tables in $out/tour_vs_lkh.md.
set -euo pipefail
# MOYO may be relative to where the script was started from.
if [ -n "${MOYO:-}" ] && [[ "$MOYO" == */* ]]; then MOYO=$(realpath "$MOYO"); fi
# shellcheck source=bench/lib.sh
source "$(dirname "$0")/lib.sh"

venv=target/vpype-venv
if ! "$venv/bin/python" -c "import vpype, elkai, numpy" 2>/dev/null; then
  python3 -m venv "$venv"
  "$venv/bin/pip" install --quiet --disable-pip-version-check "vpype==1.15.0" numpy "elkai==2.0.1"
fi
py=$venv/bin/python
if [ -z "${MOYO:-}" ]; then
  cargo build --release --quiet --bin moyo
fi
moyo=${MOYO:-target/release/moyo}

travel() { "$py" bench/svg_metrics.py "$1" | "$py" -c "import json,sys; print(round(json.load(sys.stdin)['pen_up_mm']))"; }
ratio() { "$py" -c "print(f'{$1 / $2:.3f}' if $2 else '–')"; }
# CPU seconds (user + system) of a command, the best of three.
cpu() {
  local best=
  for _ in 1 2 3; do
    /usr/bin/time -f "%U %S" -o "$work/time" "$@" > /dev/null 2>&1
    best=$(awk -v b="$best" '{ t = $1 + $2; if (b == "" || t < b) b = t; print b }' "$work/time")
  done
  echo "$best"
}

templates=("$@")
if [ ${#templates[@]} -eq 0 ]; then
  mapfile -t templates < <("$moyo" templates | awk '{print $1}')
fi

{
  echo "### 1,500 random segments"
  echo
  echo "| tool | pen-up mm | × LKH |"
  echo "|---|---:|---:|"
  "$py" bench/tours.py segments 1500 "$work/seg.svg"
  "$moyo" plot "$work/seg.svg" --sort -o "$work/seg.moyo.svg" 2> /dev/null
  "$venv/bin/vpype" read "$work/seg.svg" linesort --two-opt write "$work/seg.vpype.svg"
  lkh=$("$py" bench/tours.py lkh "$work/seg.svg" | "$py" -c "import json,sys; print(round(json.load(sys.stdin)['pen_up_mm']))")
  m=$(travel "$work/seg.moyo.svg"); v=$(travel "$work/seg.vpype.svg")
  echo "| LKH (elkai 2.0.1, 1 run) | $lkh | 1.000 |"
  echo "| vpype linesort --two-opt | $v | $(ratio "$v" "$lkh") |"
  echo "| moyo plot --sort | $m | $(ratio "$m" "$lkh") |"
  echo "$m $lkh" > "$work/lkh"
  echo
  echo "### Every template's largest layer, shuffled"
  echo
  echo "| template | layer | paths | vpype two-opt mm | moyo mm | moyo / vpype |"
  echo "|---|---|---:|---:|---:|---:|"
  : > "$work/ratios"
  for t in "${templates[@]}"; do
    if ! "$moyo" render -t "$t" -o "$work/t.svg" > /dev/null 2>&1; then
      echo "| $t | render failed |||||"
      continue
    fi
    info=$("$py" bench/tours.py largest "$work/t.svg" "$work/t.largest.svg")
    "$moyo" plot "$work/t.largest.svg" --sort -o "$work/t.moyo.svg" 2> /dev/null
    "$venv/bin/vpype" read "$work/t.largest.svg" linesort --two-opt write "$work/t.vpype.svg"
    m=$(travel "$work/t.moyo.svg"); v=$(travel "$work/t.vpype.svg")
    r=$(ratio "$m" "$v")
    echo "$r $t" >> "$work/ratios"
    echo "| $t | ${info% *} | ${info##* } | $v | $m | $r |"
  done
  echo
  echo "### 100,000 random paths"
  echo
  python3 bench/gen_paths.py random 100000 "$work/r100k.svg"
  plain=$(cpu "$moyo" plot "$work/r100k.svg" -o "$work/r.svg")
  sorted=$(cpu "$moyo" plot "$work/r100k.svg" --sort -o "$work/r.svg")
  echo "moyo plot: $plain s CPU; with --sort: $sorted s CPU"
  sort_s=$("$py" -c "print(f'{$sorted - $plain:.2f}')")
  echo
  read -r m lkh < "$work/lkh"
  worst=$(sort -rn "$work/ratios" | head -1)
  echo "**Ratios:** moyo / LKH on 1,500 segments $(ratio "$m" "$lkh") (target ≤ 1.05); worst moyo / vpype two-opt over ${#templates[@]} templates' largest layers ${worst:-–} (target ≤ 1.00); sort of 100,000 paths $sort_s s CPU (target < 1 s)"
} | tee "$out/tour_vs_lkh.md"
