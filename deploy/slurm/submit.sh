#!/bin/bash
# Submit a sweep as a Slurm job array of N shards and a collect job that starts when every
# shard has succeeded.
#   deploy/slurm/submit.sh SPEC.toml OUT_DIR N [extra sbatch flags, e.g. --partition=short]
set -euo pipefail
SPEC=${1:?usage: submit.sh SPEC.toml OUT_DIR N [sbatch flags]}
OUT=${2:?usage: submit.sh SPEC.toml OUT_DIR N [sbatch flags]}
N=${3:?usage: submit.sh SPEC.toml OUT_DIR N [sbatch flags]}
shift 3
HERE=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$OUT"
array=$(sbatch --parsable "$@" --array=1-"$N" "$HERE/sweep.sbatch" "$SPEC" "$OUT")
collect=$(sbatch --parsable "$@" --dependency=afterok:"${array%%;*}" "$HERE/collect.sbatch" "$SPEC" "$OUT")
echo "array job $array ($N shards), collect job $collect; results in $OUT/summary.md"
