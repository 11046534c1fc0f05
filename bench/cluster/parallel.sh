#!/bin/sh
# Runs a planned study (`penumbra study plan STUDY -o DIR`) with GNU parallel: every job of
# DIR/jobs.jsonl as `penumbra study run DIR --index I` (docs/studies.md), on this machine or over
# ssh on HOSTS (GNU parallel's -S: "host1,host2" or "4/host1,:" ...; each must see DIR and the
# binary at the same paths), then `penumbra study merge DIR`. GNU parallel's job log
# (DIR/parallel.joblog) and --resume skip what a previous run did; `study run` itself skips a
# job whose row exists, so rerunning after an interruption resumes either way.
#
#   bench/cluster/parallel.sh DIR [HOSTS]
#
# Environment: PENUMBRA (the binary, default: penumbra on PATH), JOBS (job slots per host,
# default: one per core).
set -eu
[ $# -ge 1 ] || { echo "usage: $0 DIR [HOSTS]" >&2; exit 2; }
DIR=$(cd "$1" && pwd)
HOSTS=${2:-}
PENUMBRA=${PENUMBRA:-penumbra}
case "$PENUMBRA" in */*) PENUMBRA=$(cd "$(dirname "$PENUMBRA")" && pwd)/$(basename "$PENUMBRA") ;; esac
[ -f "$DIR/jobs.jsonl" ] || { echo "$0: $DIR/jobs.jsonl: no plan (run penumbra study plan first)" >&2; exit 2; }
N=$(grep -c . "$DIR/jobs.jsonl")
set -- --joblog "$DIR/parallel.joblog" --resume --jobs "${JOBS:-100%}" --halt never
[ -n "$HOSTS" ] && set -- "$@" -S "$HOSTS"
rc=0
seq 0 $((N - 1)) | parallel "$@" "'$PENUMBRA'" study run "'$DIR'" --index '{}' || rc=$?
"$PENUMBRA" study merge "$DIR" || merged=$?
[ "$rc" -ne 0 ] && echo "$0: $rc of $N jobs failed (their rows say why; DIR/parallel.joblog)" >&2
exit $((rc != 0 ? 1 : ${merged:-0}))
