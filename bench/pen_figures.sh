#!/usr/bin/env bash
# What a pen plotter meets in every built-in template, measured by
# bench/pen_metrics.py (independent of moyo's code):
#
#   bench/pen_figures.sh                   # every template
#   bench/pen_figures.sh kimono-1 lsystem-koch
#   MOYO=path/to/moyo bench/pen_figures.sh # another binary
#
# Builds nothing: uses target/release/moyo (or $MOYO). Creates the Python
# virtual environment target/vpype-venv (vpype, numpy) when missing. For each
# template:
#   moyo render -t NAME -o DIR/NAME.svg
#   moyo plot DIR/NAME.svg -o DIR/NAME.sorted.svg --merge --sort
# and prints one markdown row: polylines (one per subpath: one pen lift
# each), pen-up travel (m, in file order from the sheet's top-left corner,
# each pen from there), estimated plot time (h:mm; 25 mm/s down, 75 mm/s up,
# 0.3 s a lift), pen-up travel against that of the --merge --sort result
# (× : how much travel plot would save), line drawn twice (% of pen-down:
# lines running together for two pen widths or more), ink shared where
# lines touch at a shallow angle (% of pen-down, forks and corners
# included), debris (% of polylines: shorter than the pen is wide and
# within a pen width of other line work) and the densest 1 mm cell as multiples of solid ink
# (line length × pen width). See pen_metrics.py for the exact definitions.
# SVGs and per-template JSON stay in DIR = $out/pen (target/bench/pen); the
# table goes to $out/pen_figures.md.
set -euo pipefail
# MOYO may be relative to where the script was started from.
if [ -n "${MOYO:-}" ] && [[ "$MOYO" == */* ]]; then MOYO=$(realpath "$MOYO"); fi
# shellcheck source=bench/lib.sh
source "$(dirname "$0")/lib.sh"

moyo=${MOYO:-target/release/moyo}
venv=target/vpype-venv
if [ ! -x "$venv/bin/python" ] || ! "$venv/bin/python" -c "import vpype, numpy" 2>/dev/null; then
  python3 -m venv "$venv"
  "$venv/bin/pip" install --quiet --disable-pip-version-check "vpype==1.15.0" numpy
fi
py=$venv/bin/python
dir=$out/pen
mkdir -p "$dir"

templates=("$@")
if [ ${#templates[@]} -eq 0 ]; then
  mapfile -t templates < <("$moyo" templates | cut -f1 | awk '{print $1}')
fi

started=$(date +%s.%N)
{
  echo "| template | paths | pen-up m | plot h:mm | pen-up × sorted | doubled % | touching % | debris % | densest × solid |"
  echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|"
  for t in "${templates[@]}"; do
    if ! "$moyo" render -t "$t" -o "$dir/$t.svg" > /dev/null 2> "$work/stderr"; then
      echo "| $t | render failed: $(head -c 200 "$work/stderr" | tr '\n|' '  ') ||||||||"
      continue
    fi
    "$py" bench/pen_metrics.py --json "$dir/$t.svg" > "$dir/$t.json"
    if "$moyo" plot "$dir/$t.svg" -o "$dir/$t.sorted.svg" --merge --sort > /dev/null 2> "$work/stderr"; then
      "$py" bench/pen_metrics.py --json --travel-only "$dir/$t.sorted.svg" > "$dir/$t.sorted.json"
    else
      echo '{"total": {"pen_up_mm": null}}' > "$dir/$t.sorted.json"
    fi
    "$py" - "$t" "$dir/$t.json" "$dir/$t.sorted.json" <<'EOF'
import json, sys
name, a, b = sys.argv[1:]
m = json.load(open(a))["total"]
sorted_up = json.load(open(b))["total"]["pen_up_mm"]
s = int(round(m["plot_time_s"] / 60))
ratio = ("plot failed" if sorted_up is None else
         f"{m['pen_up_mm'] / sorted_up:.2f}" if sorted_up > 0 else "–")
print(f"| {name} | {m['paths']} | {m['pen_up_mm'] / 1000:.1f} | {s // 60}:{s % 60:02} | {ratio} "
      f"| {m['doubled_pct']:.1f} | {m['touching_pct']:.1f} | {m['debris_pct']:.1f} | {m['densest_solid']:.1f} |")
EOF
  done
} | tee "$out/pen_figures.md"
echo "$(date +%s.%N) $started ${#templates[@]}" | awk '{printf "%d templates in %.0f s\n", $3, $1 - $2}' >&2
