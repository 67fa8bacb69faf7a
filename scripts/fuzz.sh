#!/usr/bin/env bash
# Coverage-guided fuzzing with libFuzzer on the stable toolchain (docs/robustness.md,
# "Coverage-guided fuzzing"). Builds fuzz/ (its own workspace, instrumented by
# fuzz/.cargo/config.toml) and runs each target from its seed corpus (fuzz/seeds/TARGET) with a
# working corpus in fuzz/corpus-run/TARGET. A crash, a panic, a timeout (10 s) or more than
# 4 GiB of memory fails the script, the input kept in fuzz/artifacts/TARGET/.
#
#   scripts/fuzz.sh                 every target for 3 s (the smoke run of scripts/test-all.sh)
#   scripts/fuzz.sh 600             every target for 10 minutes
#   scripts/fuzz.sh runs=1000000 scenario pems   one million inputs each of two targets
set -euo pipefail
cd "$(dirname "$0")/../fuzz"

budget=${1:-3}
[ $# -gt 0 ] && shift
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(scenario set_value sweep_spec run_files pems sumo sumo_shapes)
case "$budget" in
    runs=*) limit=(-runs="${budget#runs=}") ;;
    *) limit=(-max_total_time="$budget") ;;
esac

# An explicit --target keeps the coverage flags off build scripts and proc macros.
host=$(rustc -vV | sed -n 's/^host: //p')
cargo build --release --target "$host" --bins --quiet
# The run-file and field targets write their input to a file: a RAM disk where there is one.
if [ -d /dev/shm ] && [ -w /dev/shm ]; then export TMPDIR=/dev/shm; fi

for t in "${targets[@]}"; do
    mkdir -p "corpus-run/$t" "artifacts/$t"
    log="artifacts/$t/last-run.log"
    if ! "./target/$host/release/$t" "corpus-run/$t" "seeds/$t" "${limit[@]}" \
        -max_len=16384 -timeout=10 -rss_limit_mb=4096 -artifact_prefix="artifacts/$t/" \
        -print_final_stats=1 >"$log" 2>&1; then
        tail -n 40 "$log" >&2
        echo "error: fuzz target $t failed; the input is in fuzz/artifacts/$t/" >&2
        exit 1
    fi
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
    cov=$(grep -o 'cov: [0-9]*' "$log" | tail -n 1)
    ft=$(grep -o 'ft: [0-9]*' "$log" | tail -n 1)
    echo "fuzz $t: $runs inputs, $cov edges, $ft features, no crash"
done
