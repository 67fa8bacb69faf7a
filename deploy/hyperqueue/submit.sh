#!/bin/bash
# Submit a sweep to a running HyperQueue server as an array of N tasks (task ids 0..N-1:
# platoonsim runs shard HQ_TASK_ID+1 of --shards N), wait for it, then collect the tables.
# HyperQueue runs on a laptop, a workstation or inside a Slurm/PBS allocation
# (`hq server start &`, then `hq worker start &` on each node, or its automatic allocation).
#   deploy/hyperqueue/submit.sh SPEC.toml OUT_DIR N [CPUS_PER_TASK]
set -euo pipefail
SPEC=${1:?usage: submit.sh SPEC.toml OUT_DIR N [CPUS_PER_TASK]}
OUT=${2:?usage: submit.sh SPEC.toml OUT_DIR N [CPUS_PER_TASK]}
N=${3:?usage: submit.sh SPEC.toml OUT_DIR N [CPUS_PER_TASK]}
CPUS=${4:-1}
mkdir -p "$OUT"
job=$(hq --output-mode quiet submit --array 0-$((N - 1)) --cpus "$CPUS" \
    --stdout "$OUT/hq-%{TASK_ID}.log" --stderr "$OUT/hq-%{TASK_ID}.log" \
    -- platoonsim sweep "$SPEC" --out "$OUT" --shards "$N" --jobs "$CPUS")
echo "HyperQueue job $job: $N shards"
hq job wait "$job"
platoonsim sweep "$SPEC" --out "$OUT" --collect
