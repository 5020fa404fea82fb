# Shared by the bench scripts that compare moyo with another program
# (source it after `set -euo pipefail`): works from the crate root, puts
# results in $out (BENCH_OUT, default target/bench) and scratch files in
# $work (removed on exit), and gives `measure`.
cd "$(dirname "${BASH_SOURCE[0]}")/.."
out=${BENCH_OUT:-target/bench}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"

# Wall seconds and peak RSS (KiB) of a command, via GNU time.
measure() {
  /usr/bin/time -f "%e %M" -o "$work/time" "$@" > /dev/null 2> "$work/stderr" || {
    cat "$work/stderr" >&2
    return 1
  }
  cat "$work/time"
}
