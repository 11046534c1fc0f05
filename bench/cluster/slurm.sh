#!/bin/sh
# Runs a planned study (`penumbra study plan STUDY -o DIR`) on Slurm: one array task per job of
# DIR/jobs.jsonl, each `penumbra study run DIR --index $SLURM_ARRAY_TASK_ID` (docs/studies.md),
# then `penumbra study merge DIR` as a job that starts after the array (afterany: a failed job is
# a failed row in the report, not a reason not to merge). DIR must be on a file system every node
# sees; jobs run in any order (a job renders the references it needs when their jobs have not
# run yet, under a lock), and a job whose row exists is skipped, so resubmitting resumes.
#
#   bench/cluster/slurm.sh DIR [sbatch options...]
#     e.g. bench/cluster/slurm.sh /shared/study --partition=gpu --gres=gpu:1 --time=00:30:00
#
# Environment: PENUMBRA (the binary, default: penumbra on PATH), MAX_RUNNING (array tasks at
# once, default 64), WAIT=1 (wait for the merge job to end: sbatch --wait). Arrays longer than the
# cluster's MaxArraySize are submitted in several arrays. Prints the job ids it submitted.
set -eu
[ $# -ge 1 ] || { echo "usage: $0 DIR [sbatch options...]" >&2; exit 2; }
DIR=$(cd "$1" && pwd); shift
PENUMBRA=${PENUMBRA:-penumbra}
case "$PENUMBRA" in */*) PENUMBRA=$(cd "$(dirname "$PENUMBRA")" && pwd)/$(basename "$PENUMBRA") ;; esac
[ -f "$DIR/jobs.jsonl" ] || { echo "$0: $DIR/jobs.jsonl: no plan (run penumbra study plan first)" >&2; exit 2; }
N=$(grep -c . "$DIR/jobs.jsonl")
MAX_RUNNING=${MAX_RUNNING:-64}
MAX_ARRAY=$(scontrol show config 2>/dev/null | awk '$1 == "MaxArraySize" {print $3}')
MAX_ARRAY=${MAX_ARRAY:-1001}
mkdir -p "$DIR/slurm"
ids=""
offset=0
while [ "$offset" -lt "$N" ]; do
  count=$((N - offset))
  [ "$count" -gt "$MAX_ARRAY" ] && count=$MAX_ARRAY
  id=$(sbatch --parsable --job-name=penumbra-study --array="0-$((count - 1))%$MAX_RUNNING" \
    --output="$DIR/slurm/%A_%a.out" "$@" \
    --wrap "exec '$PENUMBRA' study run '$DIR' --index \$((\$SLURM_ARRAY_TASK_ID + $offset))")
  id=${id%%;*}
  echo "submitted array $id: jobs $offset-$((offset + count - 1)) of $N"
  ids="$ids${ids:+:}$id"
  offset=$((offset + count))
done
wait_flag=""
[ "${WAIT:-0}" = 1 ] && wait_flag="--wait"
merge=$(sbatch --parsable $wait_flag --job-name=penumbra-merge --dependency="afterany:$ids" \
  --output="$DIR/slurm/merge_%j.out" "$@" --wrap "exec '$PENUMBRA' study merge '$DIR'") || merged=$?
echo "submitted merge ${merge%%;*} (after $ids): report in $DIR/report/index.html"
exit "${merged:-0}"
