#!/usr/bin/env bash
# One Slurm array task of a sweep: renders the task's shard into results/<config>-shard-<i>.
#   sbatch --array=0-7 scripts/slurm_sweep.sh configs/X.json [extra sst-eval sweep options]
#   (when all tasks are done)  sst-eval merge results/X-shard-* -o results/X
# sst-eval reads SLURM_ARRAY_TASK_ID/_MIN/_COUNT itself; the reference cache should be on a
# shared file system (SST_CACHE_DIR) so that tasks reuse each other's references.
#SBATCH --job-name=sst-sweep
#SBATCH --cpus-per-task=16
#SBATCH --time=04:00:00
set -euo pipefail
config="$1"
shift
name="$(basename "$config" .json)"
index=$((SLURM_ARRAY_TASK_ID - ${SLURM_ARRAY_TASK_MIN:-0}))
exec ./build/sst-eval sweep "$config" -o "results/$name-shard-$index" --resume "$@"
