#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, AddressSanitizer, UndefinedBehaviorSanitizer) and runs each
# for a bounded time, seeded from assets/scenes, assets/bench, tests/fuzz/corpus and the saved
# regressions. A crash, a sanitizer report, an input running over 10 s (a hang) or over 2 GiB
# (exhausting the machine) fails the run; the input is left in <build>/artifacts/<target>/, to be
# copied to tests/fuzz/regressions/<kind>/ once fixed (test_fuzz_regressions.cpp replays them).
# libFuzzer saves an input that took over 10 s but finished as slow-unit-*; such an input is
# replayed three times on its own and counts only if a replay is still slow (over 2 s): a stall of
# the machine (CI once saw one) is not the input's doing. Either way it is printed in base64, so
# the CI log alone is enough to reproduce it.
#   tests/fuzz/run.sh [seconds per target, default 60] [build folder, default build-fuzz]
set -euo pipefail
cd "$(dirname "$0")/../.."
seconds=${1:-60}
build=${2:-build-fuzz}
cmake -S tests/fuzz -B "$build" -G Ninja -DCMAKE_CXX_COMPILER=clang++ > /dev/null
cmake --build "$build" -j"${JOBS:-$(nproc)}"

# One target: fuzz it, replay any slow unit, and leave its summary line in $build/$target.result
# and its status in $build/$target.status. Targets run $JOBS at a time (each is single-threaded),
# so the stage takes seconds x targets / cores.
fuzz_one() {
    local target=$1 seeds dict max_len
    case $target in
    scene) seeds=(assets/scenes tests/fuzz/corpus/scene tests/fuzz/regressions/scene); dict=scene.dict; max_len=16384 ;;
    obj) seeds=(tests/fuzz/corpus/obj tests/fuzz/regressions/obj); dict=obj.dict; max_len=16384 ;;
    bench_spec) seeds=(assets/bench tests/fuzz/corpus/bench tests/fuzz/regressions/bench); dict=bench.dict; max_len=8192 ;;
    tour) seeds=(assets/tours tests/fuzz/corpus/tour tests/fuzz/regressions/tour); dict=tour.dict; max_len=16384 ;;
    session) seeds=(tests/fuzz/corpus/session tests/fuzz/regressions/session); dict=tour.dict; max_len=8192 ;;
    path) seeds=(assets/stress tests/fuzz/corpus/path tests/fuzz/regressions/path); dict=path.dict; max_len=16384 ;;
    texture) seeds=(tests/fuzz/corpus/texture tests/fuzz/regressions/texture); dict=png.dict; max_len=65536 ;;
    esac
    local corpus="$build/corpus/$target" artifacts="$build/artifacts/$target" log="$build/$target.log"
    local code runs unit slowest ms replay found status=0
    mkdir -p "$corpus" "$artifacts"
    echo "fuzz_$target: ${seconds}s"
    set +e
    UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
        "$build/fuzz_$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len="$max_len" \
        -dict="tests/fuzz/$dict" -artifact_prefix="$artifacts/" -print_final_stats=1 \
        "$corpus" "${seeds[@]}" > "$log" 2>&1
    code=$?
    set -e
    runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo "?")
    for unit in "$artifacts"/slow-unit-*; do
        [ -e "$unit" ] || continue
        echo "fuzz_$target: $(basename "$unit") ($(stat -c %s "$unit") bytes), base64:"
        base64 -w 120 "$unit"
        slowest=0
        for replay in 1 2 3; do
            ms=$({ "$build/fuzz_$target" "$unit" 2>&1 || true; } | grep -o 'in [0-9]* ms' | grep -o '[0-9]*' | head -1 || true)
            ms=${ms:-999999}   # no time printed: it crashed on replay, which is a finding
            echo "fuzz_$target: replay $replay took $ms ms"
            [ "$ms" -gt "$slowest" ] && slowest=$ms
        done
        if [ "$slowest" -le 2000 ]; then
            echo "fuzz_$target: not slow when replayed (at most $slowest ms): a stall of the machine, not a finding"
            mkdir -p "$build/stalls/$target"
            mv "$unit" "$build/stalls/$target/"
        fi
    done
    found=$(ls "$artifacts" | wc -l)
    echo "fuzz_$target: $runs executions in ${seconds}s, exit $code, $found finding(s)" > "$build/$target.result"
    if [ "$code" != 0 ] || [ "$found" != 0 ]; then
        status=1
        { echo "fuzz_$target FAILED (exit $code); the end of $log:"; tail -40 "$log"; ls -l "$artifacts"; } \
            > "$build/$target.failure"
    fi
    echo "$status" > "$build/$target.status"
}

targets=(scene obj bench_spec tour session path texture)
jobs=${JOBS:-$(nproc)}
rm -f "$build"/*.result "$build"/*.status "$build"/*.failure
for target in "${targets[@]}"; do
    while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do wait -n || true; done
    fuzz_one "$target" &
done
wait
status=0
summary=""
for target in "${targets[@]}"; do
    if [ -e "$build/$target.failure" ]; then cat "$build/$target.failure"; fi
    summary+="$(cat "$build/$target.result" 2>/dev/null || echo "fuzz_$target: no result (the runner died)")"$'\n'
    [ "$(cat "$build/$target.status" 2>/dev/null || echo 1)" = 0 ] || status=1
done
printf '%s' "$summary"
exit $status
