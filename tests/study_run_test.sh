#!/bin/sh
# A study run end to end (docs/studies.md) on tests/studies/tiny.json: 2 scenes x 3 techniques x
# 2 sample counts x 2 seeds = 24 technique jobs, 8 same-sample and 2 converged references.
# Usage: study_run_test.sh PENUMBRA EXR_DIFF SRCDIR MODE, MODE one of
#   local     plan, run with -j 2, merge; a second run renders nothing (no row rewritten); two
#             rows and one image deleted: exactly those three jobs rerun; --index --force;
#   shards    the same plan run whole in one process and elsewhere in two shards (one with a
#             process a job): the same ids, bit-identical images and the same CSV (timings aside);
#   failed    a scene whose texture is cut short (its header whole: the plan loads it, the jobs do
#             not): its reference job fails with the texture named, its technique jobs fail
#             naming their reference, the other scene's jobs go on; the run and the merge exit 1,
#             the report lists the failures; a rerun redoes nothing, --retry-failed redoes
#             exactly the failed jobs; the texture mended, a new plan renders only its scene's;
#   kill      runs killed with SIGKILL at several moments until one finishes: after every kill a
#             job left half done (its temporary folder) has no row, and the finished study's CSV
#             equals an uninterrupted run's (timings aside);
#   parallel  bench/cluster/parallel.sh with GNU parallel, 2 job slots; a second call resumes
#             (nothing rerun);
#   axes      tests/studies/axes.json: light scales, a profiled technique, parts, an opaque twin
#             made in memory and two shading modes: hard-sv's error grows with the light and
#             dcs's is 0 at every scale (light-size.md), dcs's statistics come from its profiled
#             frame (stages.md) and it agrees with the reference on every ring of the lights,
#             the twin's references differ from the semi-opaque scene's;
#   slurm     bench/cluster/slurm.sh on a real Slurm: munged, slurmctld and slurmd started on
#             localhost with a one-node slurm.conf in a temporary folder (root only; 8 slots on
#             the node, more than its cores: the jobs are short), the array and its merge job
#             submitted, waited for, the rows checked, the daemons stopped. Not root or no Slurm:
#             skipped (77), unless PENUMBRA_REQUIRE_SLURM=1 (CI), which makes that a failure.
# Exits 77 (skipped) without a GL context.
P="$1"; DIFF="$2"; SRC="$3"; MODE="$4"
T=$(mktemp -d); trap 'cleanup' EXIT
cleanup() { stop_slurm; rm -rf "$T"; }
stop_slurm() { :; }
STUDY="$SRC/tests/studies/tiny.json"
JOBS=34
SCENES="16-contact default"  # their report folders
fail() { echo "FAIL: $*"; exit 1; }

"$P" render -W 16 -H 16 --samples 1 -o "$T/probe.exr" 2>"$T/err"; rc=$?
if [ "$rc" -eq 77 ]; then echo "no GL context: skipped"; cat "$T/err"; exit 77; fi
[ "$rc" -eq 0 ] || { cat "$T/err"; fail "probe render exited $rc"; }

plan() {  # plan DIR
  "$P" study plan "$STUDY" -o "$1" > "$T/plan.out" 2>&1 || { cat "$T/plan.out"; fail "study plan exited $?"; }
  grep -q "$JOBS jobs" "$T/plan.out" || { cat "$T/plan.out"; fail "plan: not $JOBS jobs"; }
}
run() {  # run DIR EXPECTED-SUMMARY [flags...]: study run, its summary line checked
  d="$1"; want="$2"; shift 2
  "$P" study run "$d" "$@" > "$T/run.out" 2>"$T/run.err" || { cat "$T/run.out" "$T/run.err"; fail "study run $* exited $?"; }
  grep -q "$want" "$T/run.out" || { cat "$T/run.out"; tail -n 20 "$T/run.err"; fail "study run $*: expected '$want'"; }
}
merge() {  # merge DIR
  "$P" study merge "$1" > "$T/merge.out" 2>&1 || { cat "$T/merge.out"; fail "study merge exited $?"; }
  grep -q "$JOBS jobs: $JOBS done, 0 failed, 0 missing" "$T/merge.out" || { cat "$T/merge.out"; fail "merge: not all done"; }
  [ "$(grep -c . "$1/results.csv")" -eq $((JOBS + 1)) ] || fail "results.csv: not $JOBS rows"
  [ "$(grep -c . "$1/results.jsonl")" -eq "$JOBS" ] || fail "results.jsonl: not $JOBS rows"
  for f in report/index.html report/headline.svg report/headline.md; do
    [ -s "$1/$f" ] || fail "merge wrote no $f"
  done
  for scene in $SCENES; do
    [ -s "$1/report/$scene/index.html" ] && [ -s "$1/report/$scene/report.json" ] || fail "no report of $scene"
    grep -q '"status": "failed"' "$1/report/$scene/report.json" && fail "a failed run in the report of $scene"
  done
  return 0
}
# The CSV without its timing columns (total_ms*, prepare_ms, date, seconds), sorted by id.
stable_csv() {
  awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i ~ /^(total_ms.*|prepare_ms|date|seconds)$/) drop[i] = 1 }
           { line = ""; for (i = 1; i <= NF; i++) line = line (i > 1 ? "," : "") (drop[i] ? "" : $i); print line }' "$1" | sort
}
same_results() {  # same_results DIR-A DIR-B: the same rows but timings, bit-identical images
  stable_csv "$1/results.csv" > "$T/a.csv"; stable_csv "$2/results.csv" > "$T/b.csv"
  cmp -s "$T/a.csv" "$T/b.csv" || { diff "$T/a.csv" "$T/b.csv" | head -n 20; fail "results.csv differ (timings aside)"; }
  n=0
  for f in $(cd "$1/jobs" && find . -name '*.png' -o -name '*.exr' -o -name '*.bin'); do
    [ -f "$2/jobs/$f" ] || fail "$f: only in $1"
    case "$f" in
      *.exr) "$DIFF" "$1/jobs/$f" "$2/jobs/$f" > "$T/diff" 2>&1 || { cat "$T/diff"; fail "$f differ"; } ;;
      *) cmp -s "$1/jobs/$f" "$2/jobs/$f" || fail "$f differ" ;;
    esac
    n=$((n + 1))
  done
  [ "$n" -gt "$JOBS" ] || fail "only $n images compared"
  echo "same results: $(($(grep -c . "$T/a.csv") - 1)) rows, $n images bit-identical"
}
technique_ids() { grep '"kind":"technique"' "$1/jobs.jsonl" | sed 's/.*"id":"\([0-9a-f]*\)".*/\1/'; }

case "$MODE" in
local)
  plan "$T/a"
  run "$T/a" "$JOBS jobs selected: $JOBS rendered, 0 already done, 0 failed" -j 2
  merge "$T/a"
  touch "$T/marker"; sleep 1
  run "$T/a" "0 rendered, $JOBS already done" -j 2
  run "$T/a" "0 rendered, $JOBS already done"
  [ -z "$(find "$T/a/jobs" -name row.json -newer "$T/marker")" ] || fail "a second run rewrote rows"
  set -- $(technique_ids "$T/a" | head -n 3)
  rm "$T/a/jobs/$1/row.json" "$T/a/jobs/$2/row.json"
  rm "$(ls "$T/a/jobs/$3/"*.png | head -n 1)"
  touch "$T/marker"; sleep 1
  run "$T/a" "$JOBS jobs selected: 3 rendered, $((JOBS - 3)) already done, 0 failed" -j 2
  rewritten=$(find "$T/a/jobs" -name row.json -newer "$T/marker" | sed 's|.*/jobs/\([0-9a-f]*\)/row.json|\1|' | sort)
  [ "$rewritten" = "$(printf '%s\n' "$1" "$2" "$3" | sort)" ] || fail "rerun rewrote: $rewritten (not $1 $2 $3)"
  [ -z "$(ls -d "$T/a/jobs/"*.tmp "$T/a/jobs/"*.old 2>/dev/null)" ] || fail "temporary folders left"
  run "$T/a" "1 jobs selected: 1 rendered, 0 already done, 0 failed" --index 20 --force
  merge "$T/a"
  ;;
shards)
  plan "$T/a"
  run "$T/a" "$JOBS jobs selected: $JOBS rendered, 0 already done, 0 failed"
  merge "$T/a"
  plan "$T/b"
  [ "$(cat "$T/a/jobs.jsonl")" = "$(cat "$T/b/jobs.jsonl")" ] || fail "the same study planned twice gave different jobs"
  # Shard 1 (a process a job) renders the references its jobs read (jobs of shard 0) on the way:
  # shard 0 (one process) finds those done.
  run "$T/b" "$((JOBS / 2)) jobs selected: $((JOBS / 2)) rendered, 0 already done, 0 failed" --shard 1/2 -j 2
  run "$T/b" "$((JOBS / 2)) jobs selected: .* 0 failed" --shard 0/2
  merge "$T/b"
  same_results "$T/a" "$T/b"
  ;;
failed)
  mkdir -p "$T/f/textures"
  cp "$SRC/scenes/stained-glass.json" "$T/f/"
  head -c 2000 "$SRC/scenes/textures/stained-glass.png" > "$T/f/textures/stained-glass.png"
  printf '{"scenes": ["stained-glass.json", "default"], "techniques": ["dcs", "pcss"], "samples": 8, "sizes": 64, "frames": 1, "warmup": 0}\n' > "$T/f/study.json"
  STUDY="$T/f/study.json" JOBS=6 SCENES="stained-glass default"
  plan "$T/f/d"
  "$P" study run "$T/f/d" > "$T/run.out" 2>"$T/run.err" && fail "a run with failed jobs exited 0"
  grep -q "6 jobs selected: 6 rendered, 0 already done, 3 failed" "$T/run.out" || { cat "$T/run.out"; fail "not 3 failed"; }
  [ "$(grep -l '"status":"failed"' "$T/f/d/jobs/"*/row.json | wc -l)" -eq 3 ] || fail "not 3 failed rows"
  grep -q 'stained-glass.png: truncated or corrupt PNG' "$T/f/d/jobs/"*/row.json || fail "no row names the texture"
  [ "$(grep -l 'its reference job [0-9a-f]* failed' "$T/f/d/jobs/"*/row.json | wc -l)" -eq 2 ] || fail "technique rows do not name their reference"
  "$P" study merge "$T/f/d" > "$T/merge.out" 2>&1 && fail "a merge with failed jobs exited 0"
  grep -q "6 jobs: 3 done, 3 failed, 0 missing" "$T/merge.out" || { cat "$T/merge.out"; fail "merge: not 3 failed"; }
  [ "$(grep -c '^failed ' "$T/f/d/report/status.txt")" -eq 3 ] || fail "status.txt does not list the 3 failures"
  grep -q '"status": "failed"' "$T/f/d/report/stained-glass/report.json" || fail "the scene's report has no failed run"
  # A failed run keeps its technique's family (pcss: a single map) in the report.
  tr -d ' \n' < "$T/f/d/report/stained-glass/report.json" | grep -q '"error":"[^"]*","family":"singlemap","flipHeat":"","heat":"","height":[0-9]*,"image":"","insets":\[\],"name":"pcss"' ||
    fail "the failed pcss run is not of the single-map family"
  grep -q ',failed,.*truncated or corrupt PNG' "$T/f/d/results.csv" || fail "results.csv lacks the failure"
  "$P" study run "$T/f/d" > "$T/run.out" 2>&1
  grep -q "0 rendered, 6 already done, 3 failed" "$T/run.out" || { cat "$T/run.out"; fail "a rerun redid jobs"; }
  touch "$T/marker"; sleep 1
  "$P" study run "$T/f/d" --retry-failed > "$T/run.out" 2>&1
  grep -q "3 rendered, 3 already done, 3 failed" "$T/run.out" || { cat "$T/run.out"; fail "--retry-failed"; }
  [ "$(find "$T/f/d/jobs" -name row.json -newer "$T/marker" | wc -l)" -eq 3 ] || fail "--retry-failed rewrote other rows"
  cp "$SRC/scenes/textures/stained-glass.png" "$T/f/textures/"
  plan "$T/f/d"
  run "$T/f/d" "6 jobs selected: 3 rendered, 3 already done, 0 failed"
  merge "$T/f/d"
  ;;
kill)
  plan "$T/k"
  kills=0; halfway=0
  for delay in 0.4 0.7 0.5 0.9 0.6 1.1 0.8 1.3 0.5 1.0 0.7 1.5 2 3 5 8; do
    "$P" study run "$T/k" > /dev/null 2>&1 &
    pid=$!
    sleep "$delay"
    if kill -9 "$pid" 2>/dev/null; then
      wait "$pid" 2>/dev/null
      kills=$((kills + 1))
      for tmp in "$T/k/jobs/"*.tmp; do
        [ -d "$tmp" ] || continue
        id=$(basename "$tmp" | cut -d. -f1)
        [ -e "$T/k/jobs/$id/row.json" ] && fail "job $id killed half way has a row"
        halfway=$((halfway + 1))
      done
    else
      wait "$pid" || fail "the run that was not killed exited $?"
      break
    fi
  done
  echo "$kills runs killed, $halfway of them half way through a job"
  [ "$kills" -ge 2 ] && [ "$halfway" -ge 1 ] || fail "no run was killed half way through a job"
  run "$T/k" "0 failed"
  merge "$T/k"
  [ -z "$(ls -d "$T/k/jobs/"*.tmp 2>/dev/null)" ] || fail "temporary folders left after the last run"
  plan "$T/u"
  run "$T/u" "$JOBS rendered"
  merge "$T/u"
  same_results "$T/k" "$T/u"
  ;;
parallel)
  command -v parallel > /dev/null || fail "GNU parallel is not installed (setup.sh --deps installs it)"
  plan "$T/p"
  PENUMBRA="$P" JOBS=2 sh "$SRC/bench/cluster/parallel.sh" "$T/p" > "$T/par.out" 2>&1 || { cat "$T/par.out"; fail "parallel.sh exited $?"; }
  merge "$T/p"
  [ "$(grep -c . "$T/p/parallel.joblog")" -eq $((JOBS + 1)) ] || fail "the job log has not $JOBS jobs"
  touch "$T/marker"; sleep 1
  PENUMBRA="$P" JOBS=2 sh "$SRC/bench/cluster/parallel.sh" "$T/p" > "$T/par.out" 2>&1 || { cat "$T/par.out"; fail "second parallel.sh exited $?"; }
  [ "$(grep -c . "$T/p/parallel.joblog")" -eq $((JOBS + 1)) ] || fail "the resumed run ran jobs again"
  [ -z "$(find "$T/p/jobs" -name row.json -newer "$T/marker")" ] || fail "the resumed run rewrote rows"
  echo "GNU parallel: $JOBS jobs in 2 slots, resumed without rerunning"
  ;;
slurm)
  skip() {
    if [ "${PENUMBRA_REQUIRE_SLURM:-0}" = 1 ]; then fail "$*"; fi
    echo "skipped: $*"; exit 77
  }
  [ "$(id -u)" -eq 0 ] || skip "starting slurmctld, slurmd and munged needs root"
  for c in munged slurmctld slurmd sbatch squeue; do
    command -v "$c" > /dev/null || skip "no $c (setup.sh --deps installs slurm-wlm and munge)"
  done
  [ -r /etc/munge/munge.key ] || skip "no /etc/munge/munge.key (the munge package makes it)"
  S="$T/slurm"; mkdir -p "$S/state" "$S/spool" "$S/munge"
  stop_slurm() {
    for f in "$S/slurmd.pid" "$S/slurmctld.pid" "$S/munge/munged.pid"; do
      [ -f "$f" ] && kill "$(cat "$f")" 2>/dev/null
    done
    sleep 1
  }
  port=$((20000 + $$ % 20000))
  node=$(hostname -s)
  cat > "$S/slurm.conf" <<CONF
ClusterName=penumbra-test
SlurmctldHost=$node(127.0.0.1)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$S/munge/munge.socket
CredType=cred/munge
SlurmctldPort=$port
SlurmdPort=$((port + 1))
StateSaveLocation=$S/state
SlurmdSpoolDir=$S/spool
SlurmctldPidFile=$S/slurmctld.pid
SlurmdPidFile=$S/slurmd.pid
SlurmctldLogFile=$S/slurmctld.log
SlurmdLogFile=$S/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
MpiDefault=none
SchedulerParameters=sched_min_interval=0,batch_sched_delay=0
SlurmdParameters=config_overrides
NodeName=$node NodeAddr=127.0.0.1 CPUs=8 RealMemory=1000 State=UNKNOWN
PartitionName=test Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
  export SLURM_CONF="$S/slurm.conf"
  munged --socket="$S/munge/munge.socket" --pid-file="$S/munge/munged.pid" --log-file="$S/munge/munged.log" \
    --seed-file="$S/munge/seed" --force || fail "munged did not start"
  slurmctld -f "$SLURM_CONF" || { cat "$S/slurmctld.log"; fail "slurmctld did not start"; }
  slurmd -f "$SLURM_CONF" || { cat "$S/slurmd.log"; fail "slurmd did not start"; }
  for i in 1 2 3 4 5 6 7 8 9 10; do
    sinfo -h -o %t 2>/dev/null | grep -q idle && break
    sleep 0.5
  done
  sinfo -h -o %t | grep -q idle || { sinfo; cat "$S/slurmctld.log"; fail "the node did not come up"; }
  plan "$T/s"
  PENUMBRA="$P" sh "$SRC/bench/cluster/slurm.sh" "$T/s" > "$T/slurm.out" 2>&1 || {
    cat "$T/slurm.out"; tail -n 20 "$S/slurmctld.log"; fail "slurm.sh exited $?"; }
  cat "$T/slurm.out"
  # (sbatch --wait polls every few seconds; squeue, every 0.3 s, ends the wait sooner.)
  for i in $(seq 200); do
    [ -z "$(squeue -h 2>/dev/null)" ] && break
    sleep 0.3
  done
  [ -z "$(squeue -h)" ] || { squeue; fail "the jobs did not finish within a minute"; }
  [ "$(ls "$T/s/slurm/"*_*.out | grep -vc merge_)" -eq "$JOBS" ] || fail "not $JOBS array task logs"
  grep -q "$JOBS jobs: $JOBS done, 0 failed, 0 missing" "$T/s/slurm/"merge_*.out || { cat "$T/s/slurm/"merge_*.out; fail "the merge job did not find every row"; }
  merge "$T/s"
  echo "Slurm: $JOBS array tasks and the merge job"
  ;;
axes)
  STUDY="$SRC/tests/studies/axes.json"; JOBS=14; SCENES="16-contact semi-opaque"
  plan "$T/a"
  run "$T/a" "14 rendered" -j 2
  merge "$T/a"
  R="$T/a/report"
  cat "$R/light-size.md"
  # A column of results.csv by its header's name; rows of kind $2 whose column $3 is $4.
  csv() { awk -F, -v c="$1" -v k="$2" -v f="$3" -v v="$4" 'NR == 1 { for (i = 1; i <= NF; i++) n[$i] = i; next }
          $n["kind"] == k && (f == "" || $n[f] == v) { print $n[c] }' "$T/a/results.csv"; }
  row() { grep "^| $1 |" "$R/light-size.md" || fail "light-size.md has no row for $1"; }
  row hard-sv | awk -F'|' '{ exit !($3 + 0 < $4 + 0 && $4 + 0 > 0.01) }' || fail "hard-sv's error does not grow with the light"
  row dcs | awk -F'|' '{ exit !($3 + 0 == 0 && $4 + 0 == 0) }' || fail "dcs is not exact at every light scale"
  [ -s "$R/light-size-16-contact.svg" ] || fail "no light-size chart"
  grep -q "^| dcs |.*(a profiled frame (profile=true)).*profileFragments" "$R/stages.md" ||
    { cat "$R/stages.md"; fail "dcs's statistics are not its profiled frame's"; }
  grep "^| hard-sv |" "$R/stages.md" | grep -q "profiled" && fail "hard-sv's statistics say profiled"
  [ "$(csv shading technique technique dcs | sort -u | tr '\n' ' ')" = "modulate ratio " ] || fail "not both shading modes"
  # dcs agrees with the reference on every sample, on every ring of the rect lights (a ring
  # without samples, at 8 stratified samples the inner one, is empty).
  rings=$(for r in 0 1 2 3; do csv sample_agreement_ring$r technique technique dcs; done | grep . | sort | uniq -c)
  echo "dcs's agreement by ring: $rings"
  [ "$(echo "$rings" | awk '{ print $2 }')" = 1 ] && [ "$(echo "$rings" | awk '{ print $1 }')" -ge 12 ] ||
    fail "dcs's agreement by ring is not 1 on every ring with samples"
  twin=$(ls -d "$R"/semi-opaque?*opacity* 2>/dev/null | head -n 1)
  [ -s "$twin/report.json" ] || { ls "$R"; fail "no report of the opaque twin"; }
  # The references of the semi-opaque scene and of its twin, shading mode by shading mode.
  ref() { awk -F, -v v="$1" -v s="$2" 'NR == 1 { for (i = 1; i <= NF; i++) n[$i] = i; next }
          $n["kind"] == "reference" && $n["scene"] ~ /semi-opaque.json$/ && $n["variant"] == v && $n["shading"] == s {
          print $n["id"] }' "$T/a/results.csv"; }
  for shading in ratio modulate; do
    semi=$(ref "" $shading); opaque=$(ref opacity=1 $shading)
    [ -n "$semi" ] && [ -n "$opaque" ] || fail "no $shading references of the semi-opaque scene and its twin"
    cmp -s "$T/a/jobs/$semi/frame.bin" "$T/a/jobs/$opaque/frame.bin" && fail "the opaque twin's $shading reference equals the semi-opaque one's"
  done
  echo "axes: light-size curves, profiled statistics, parts, an opaque twin, two shading modes"
  ;;
*) fail "unknown mode '$MODE'" ;;
esac
echo "study $MODE: ok"
