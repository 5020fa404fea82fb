#!/usr/bin/env bash
# Runs every fuzz target for SECONDS (default 60) from the committed seed
# corpus, two at a time (one per core), then prints the executions,
# crashes and hangs of each and exits 1 if any target crashed. Needs
# cargo-afl (see README.md). Findings stay in out/<target>/default/.
set -euo pipefail
cd "$(dirname "$0")"
seconds=${1:-60}
targets=(scene_toml scene_json svg render_from obj image lsystem_rules stroke scene_extremes regions)

cargo afl build --release --locked --quiet
export AFL_SKIP_CPUFREQ=1 AFL_I_DONT_CARE_ABOUT_MISSING_CRASHES=1 AFL_NO_UI=1

run() {
    local t=$1
    rm -rf "out/$t"
    mkdir -p out
    if ! MOYO_FUZZ_TARGET=$t cargo afl fuzz -i "corpus/$t" -o "out/$t" -t 2000 -V "$seconds" \
        target/release/moyo-fuzz >"out/$t.log" 2>&1; then
        echo "$t: afl-fuzz failed; the end of out/$t.log:"
        tail -n 20 "out/$t.log"
        return 1
    fi
}

failed=0
for ((i = 0; i < ${#targets[@]}; i += 2)); do
    pids=()
    for t in "${targets[@]:i:2}"; do
        run "$t" &
        pids+=($!)
    done
    for pid in "${pids[@]}"; do
        wait "$pid" || failed=1
    done
done

count() { find "$1" -type f ! -name README.txt 2>/dev/null | wc -l; }
crashes=0
total=0
printf '%-14s %12s %8s %6s\n' target executions crashes hangs
for t in "${targets[@]}"; do
    stats="out/$t/default/fuzzer_stats"
    execs=$(awk -F' *: *' '$1 == "execs_done" { print $2 }' "$stats" 2>/dev/null || echo 0)
    c=$(count "out/$t/default/crashes")
    h=$(count "out/$t/default/hangs")
    printf '%-14s %12s %8s %6s\n' "$t" "${execs:-0}" "$c" "$h"
    crashes=$((crashes + c))
    total=$((total + ${execs:-0}))
done
echo "in all: $total executions, $crashes crashes"
if ((crashes > 0)); then
    echo "crashes (minimise them, fix, and add them to fuzz/crashers/<target>/):"
    find out/*/default/crashes -type f ! -name README.txt
    exit 1
fi
exit $failed
