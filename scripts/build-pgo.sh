#!/usr/bin/env bash
# Build platoonsim with profile-guided optimization (PGO), for long experiment sweeps.
#
#   scripts/build-pgo.sh            # writes target/pgo/release/platoonsim
#   target/pgo/release/platoonsim experiment sr99 --seeds 10
#
# Three steps: an instrumented build, a short training workload (the sweep's kinds of runs: the
# SR-99 baseline, PD and Flow-Aware at several penetrations, and the homogeneous road), then the
# optimized build with the merged profile. PGO changes how the compiler lays out and inlines the
# code, not the floating-point operations (no fast-math), so the outputs are bit-identical to the
# plain release build's (docs/performance.md, session 11, checked with cmp on detectors.csv).
# Needs llvm-profdata of the toolchain's LLVM: the rustup component llvm-tools, which this script
# installs if it is missing. Takes about 5 minutes on 2 cores.
set -euo pipefail
cd "$(dirname "$0")/.."

if ! command -v cargo >/dev/null 2>&1 && [ -x "$HOME/.cargo/bin/cargo" ]; then
    export PATH="$HOME/.cargo/bin:$PATH"
fi

host=$(rustc -vV | sed -n 's/^host: //p')
profdata="$(rustc --print sysroot)/lib/rustlib/$host/bin/llvm-profdata"
if [ ! -x "$profdata" ] && command -v rustup >/dev/null 2>&1; then
    echo "== llvm-profdata not found; installing the rustup component llvm-tools"
    rustup component add llvm-tools || rustup component add llvm-tools-preview || true
fi
if [ ! -x "$profdata" ]; then
    echo "error: $profdata is missing: PGO needs the llvm-profdata of rustc's own LLVM" \
        "(rustup component add llvm-tools)" >&2
    exit 1
fi

work=target/pgo-work
rm -rf "$work"
mkdir -p "$work/profiles"
profiles="$(pwd)/$work/profiles"

echo "== 1/3: instrumented build"
RUSTFLAGS="-Cprofile-generate=$profiles" \
    cargo build --release -p platoonsim --target-dir target/pgo-gen

echo "== 2/3: training runs (two at a time)"
bin=target/pgo-gen/release/platoonsim
train() {
    local name=$1
    shift
    "$bin" run "$@" --quiet --out "$work/$name" >/dev/null
}
# Two at a time; `wait PID` reports a failed run (and `set -e` stops the script), a plain `wait`
# would not.
train a sr99 --penetration 0.4 --seed 101 --duration 5400 & p1=$!
train b sr99 --penetration 0.8 --strategy pd --seed 101 --duration 5400 & p2=$!
wait $p1; wait $p2
train c sr99 --penetration 1.0 --seed 101 --duration 3600 & p1=$!
train d sr99 --penetration 0.6 --strategy flow-aware --seed 101 --duration 3600 & p2=$!
wait $p1; wait $p2
train e sr99 --penetration 0.0 --seed 101 --duration 3600 & p1=$!
train f homogeneous --penetration 0.5 --strategy pd --seed 101 & p2=$!
wait $p1; wait $p2

echo "== 3/3: optimized build"
"$profdata" merge -o "$work/merged.profdata" "$profiles"
RUSTFLAGS="-Cprofile-use=$(pwd)/$work/merged.profdata" \
    cargo build --release -p platoonsim --target-dir target/pgo

echo "PGO build: target/pgo/release/platoonsim"
