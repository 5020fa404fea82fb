#!/usr/bin/env bash
# moyo's weighted Voronoi stippling vs a reference Python implementation of
# Secord's method (bench/secord.py, numpy + scipy), same image, same count.
#
#   bench/stipple_vs_secord.sh                  # 10,000 stipples
#   bench/stipple_vs_secord.sh 2000 10000 20000 # custom counts
#   RELAX=50 CONVERGE= bench/stipple_vs_secord.sh # exactly 50 steps (both sides)
#
# Creates a Python virtual environment with numpy, scipy and Pillow in
# target/stipple-venv when missing, builds moyo (release, in
# $CARGO_TARGET_DIR or target/), and for each count stipples
# templates/images/portrait.jpg (300 × 400 px) into a 90 × 120 mm rectangle
# on an A5 page (the image fills it exactly):
#   moyo render desc.toml -o moyo.svg       ([[layers.voronoi]] draw = sites)
#   secord.py portrait.jpg --count N ...    (raster Lloyd, cKDTree + bincount)
# first with no relaxation (the rejection-sampled start only), then with
# RELAX weighted Lloyd steps. Both are timed with GNU time (wall s, peak
# MiB) and measured by the same independent script (bench/stipple_quality.py:
# tone fidelity, tone exponent, evenness, stray dots). Prints a Markdown
# table (python / moyo time: >1 means moyo is faster) and saves it to
# target/bench/stipple_vs_secord.md; 10,000 stipples (or the first count)
# are drawn side by side (stipple_vs_secord_side.png, the same dots for
# both) and moyo's own preview is kept (stipple_vs_secord_moyo.png).
set -euo pipefail
# shellcheck source=bench/lib.sh
source "$(dirname "$0")/lib.sh"

# ---- Relaxation settings: the one place both sides take them from. ----
# Most weighted Lloyd steps (moyo `relax`, secord.py --iterations).
RELAX=${RELAX:-200}
# Stop once a step's mean stipple movement is below this many mm (moyo
# `converge`, secord.py --converge); empty: exactly RELAX steps.
CONVERGE=${CONVERGE-0.005}
# Working raster of secord.py: non-white pixels per stipple (see its doc).
PX_PER_STIPPLE=${PX_PER_STIPPLE:-100}
# The picture: page, margin, and the rectangle the image fills (mm, from
# the top left inside the margins; 3:4 like the image).
MARGIN=12 X=17 Y=33 W=90 H=120 DOT=0.1 PEN=0.2
FRAME="$((MARGIN + X)),$((MARGIN + Y)),$W,$H"

venv=target/stipple-venv
py=$venv/bin/python
if ! "$py" -c "import numpy, scipy, PIL" 2> /dev/null; then
  python3 -m venv "$venv"
  "$venv/bin/pip" install --quiet --disable-pip-version-check \
    "numpy==2.2.6" "scipy==1.15.3" "pillow==11.3.0"
fi
cargo build --release --locked --quiet --bin moyo
moyo=${CARGO_TARGET_DIR:-target}/release/moyo
mkdir -p "$work/images"
cp templates/images/portrait.jpg "$work/images/"
image=$work/images/portrait.jpg

# The moyo description: COUNT stipples, STEPS steps (and CONVERGE when set).
describe() {
  local count=$1 steps=$2
  cat <<TOML
version = 1
seed = 3

[page]
size = "A5"
margin = $MARGIN

[[pens]]
number = 1
name = "black"
color = "#1d1d1f"
width = $PEN

[[layers]]
name = "stipples"

[[layers.voronoi]]
id = "portrait"
relax = $steps
$([ "$steps" = 0 ] || echo "${CONVERGE:+converge = $CONVERGE}")
draw = ["sites"]
dot = $DOT

[layers.voronoi.region]
polygon = [[$X, $Y], [$((X + W)), $Y], [$((X + W)), $((Y + H))], [$X, $((Y + H))]]

[layers.voronoi.sites]
distribution = "uniform"
count = $count
image = "images/portrait.jpg"
TOML
}

# Field $2 of the quality JSON line for file $1.
quality() { "$py" -c "import json,sys; v=json.load(sys.stdin)['$2']; print(v if isinstance(v, int) else f'{v:.3f}')" < "$work/q-$1.json"; }
ratio() { "$py" -c "print(f'{$1 / $2:.1f}' if $2 else 'inf')"; }
mib() { "$py" -c "print(round($1 / 1024))"; }

# Python's mean movement (mm) after steps 1, 10, 25, 50, … and the first
# step below 0.01 and 0.005 mm: what a `converge` threshold would stop at.
movement() {
  "$py" - "$work/python.json" <<'PY'
import json, sys
m = json.load(open(sys.argv[1]))["mean_movement_mm"]
at = ", ".join(f"{k}: {m[k - 1]:.4f}" for k in (1, 10, 25, 50, 100, 200) if k <= len(m))
first = lambda t: next((i + 1 for i, v in enumerate(m) if v < t), "not within the steps")
print(f"mean movement after step {at} mm; first step below 0.01 mm: {first(0.01)}, below 0.005 mm: {first(0.005)}")
PY
}

counts=("$@")
[ ${#counts[@]} -gt 0 ] || counts=(10000)
notes=()
# Drawn side by side: 10,000 stipples if run, else the first count.
drawn=${counts[0]}
for n in "${counts[@]}"; do [ "$n" != 10000 ] || drawn=10000; done
{
  echo "date: $(date -u +%Y-%m-%dT%H:%MZ), commit $(git rev-parse --short HEAD), $(nproc) cores, load before $(cut -d' ' -f1-3 /proc/loadavg)"
  echo "settings: relax = $RELAX, converge = ${CONVERGE:-none (fixed steps)}, secord.py $PX_PER_STIPPLE non-white px per stipple; cells: moyo / python"
  echo
  echo "| stipples | steps moyo / python | moyo s | python s | time python/moyo | MiB moyo / python | fidelity MAD | fidelity r | tone exponent γ | evenness CV | stray |"
  echo "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
  for n in "${counts[@]}"; do
    for steps in 0 "$RELAX"; do
      describe "$n" "$steps" > "$work/desc.toml"
      read -r mt mm < <(measure "$moyo" render "$work/desc.toml" --precision 6 -o "$work/moyo.svg")
      # moyo notes how its relaxation went: "… converged in 24 steps …".
      ms=$(grep -o '[0-9]\+ steps' "$work/stderr" | head -1 | cut -d' ' -f1 || true)
      ms=${ms:-$steps}
      args=(--count "$n" --frame "$FRAME" --iterations "$steps" --px-per-stipple "$PX_PER_STIPPLE")
      [ -z "$CONVERGE" ] || args+=(--converge "$CONVERGE")
      read -r pt pm < <(measure "$py" bench/secord.py "$image" "${args[@]}" -o "$work/python.json")
      draw=()
      if [ "$n" = "$drawn" ] && [ "$steps" = "$RELAX" ]; then
        draw=(--draw "$out/stipple_vs_secord_side.png" --dot-radius "$("$py" -c "print($DOT + $PEN / 2)")")
        measure "$moyo" render "$work/desc.toml" -o "$work/preview.svg" --png "$out/stipple_vs_secord_moyo.png" --dpi 254 > /dev/null
      fi
      "$py" bench/stipple_quality.py "$image" "$FRAME" "$work/moyo.svg" "$work/python.json" "${draw[@]}" > "$work/q.json"
      sed -n 1p "$work/q.json" > "$work/q-moyo.json"
      sed -n 2p "$work/q.json" > "$work/q-python.json"
      ps=$("$py" -c "import json; print(json.load(open('$work/python.json'))['iterations'])")
      row="| $n | $ms / $ps | $mt | $pt | $(ratio "$pt" "$mt") | $(mib "$mm") / $(mib "$pm")"
      for f in fidelity_mad fidelity_r tone_exponent evenness_cv stray; do
        row+=" | $(quality moyo $f) / $(quality python $f)"
      done
      echo "$row |"
      [ "$steps" = 0 ] || notes+=("- $n stipples, python: $(movement)")
    done
  done
  echo
  printf '%s\n' "${notes[@]}"
} | tee "$out/stipple_vs_secord.md"
