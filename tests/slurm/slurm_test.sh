#!/bin/bash
# The Slurm test (CTest label `slurm`): a single-node Slurm on this machine
# (scripts/slurm-local.sh), a 4-participant study on the grasp proxy and a 1-participant study
# on the soft hand submitted with `simulate --slurm`, each merged study compared with the same
# study run in one process (exports and analysis); then a series whose array task is cancelled
# midway, found unfinished by `simulate --status`, rerun, and completed.
#   tests/slurm/slurm_test.sh HANDLAB_CLI SOURCE_DIR WORK_DIR
set -euo pipefail
cli=$1
source_dir=$2
work=$3
protocol=$source_dir/studies/fine-manipulation-2021.json
rm -rf "$work"
mkdir -p "$work"
fail() { echo "FAIL: $*" >&2; exit 1; }

cluster=$work/cluster
"$source_dir/scripts/slurm-local.sh" start "$cluster" >/dev/null ||
  fail "Slurm did not start here (see the line above); the test cannot run without it"
trap '"$source_dir/scripts/slurm-local.sh" stop "$cluster"' EXIT
export SLURM_CONF=$cluster/slurm.conf
export PATH=$PATH:/usr/sbin

# Waits until the jobs named are no longer queued or running (at most $2 seconds).
wait_for_jobs() {
  local jobs=$1 limit=$2 waited=0
  while [ -n "$(squeue -h -j "$jobs" 2>/dev/null)" ]; do
    sleep 2
    waited=$((waited + 2))
    [ "$waited" -lt "$limit" ] || fail "jobs $jobs still queued after $limit s: $(squeue)"
  done
}
jobs_of() { awk '{print $2}' "$1/jobs.txt" | paste -sd,; }

# What a study gives: its exports, and its analysis without the file's name and creation time.
outputs() {
  local db=$1 out=$2
  "$cli" export --db "$db" --out "$out" >/dev/null
  if "$cli" analyze --db "$db" --json - 2>/dev/null | grep -v -e '"db":' -e '"created_at":' \
    >"$out/analysis.json"; then :; else echo "no analysis" >"$out/analysis.json"; fi
}
same_study() {
  local merged=$1 reference=$2 name=$3
  outputs "$merged" "$work/$name-merged"
  outputs "$reference" "$work/$name-reference"
  for f in trials.csv questionnaire.csv analysis.json; do
    cmp -s "$work/$name-merged/$f" "$work/$name-reference/$f" ||
      fail "$name: $f of the merged study differs from the one-process run"
  done
  echo "$name: merged study equals the one-process run ($(wc -l <"$work/$name-merged/trials.csv") trial rows)"
}

# 1. Four participants on the grasp proxy, a task each, in two arrays (as on a cluster whose
# MaxArraySize is 3), and one on the soft hand (one block of the study's design: four trials,
# to spare the test's time).
short=$work/one-block.json
sed -e 's/"blocks": 5/"blocks": 1/' "$protocol" >"$short"
grep -q '"blocks": 1' "$short" || fail "could not shorten $protocol"
"$cli" simulate --protocol "$protocol" --participants 4 --seed 21 --world proxy \
  --slurm "$work/proxy" --time 0:10:00 --max-array 3 >/dev/null
[ "$(grep -c '^array' "$work/proxy/jobs.txt")" = 2 ] || fail "not two arrays: $(cat "$work/proxy/jobs.txt")"
"$cli" simulate --protocol "$short" --participants 1 --seed 22 --world soft \
  --slurm "$work/soft" --time 1:00:00 >/dev/null
"$cli" simulate --protocol "$protocol" --participants 4 --seed 21 --world proxy --jobs 2 --quiet \
  --db "$work/proxy-reference.db" >/dev/null
"$cli" simulate --protocol "$short" --participants 1 --seed 22 --world soft --jobs 1 --quiet \
  --db "$work/soft-reference.db" >/dev/null
wait_for_jobs "$(jobs_of "$work/proxy"),$(jobs_of "$work/soft")" 3600
[ -e "$work/proxy/study-n4-seed21.db" ] || fail "the proxy study was not merged: $(cat "$work/proxy/logs/"*)"
[ -e "$work/soft/study-n1-seed22.db" ] || fail "the soft-hand study was not merged: $(cat "$work/soft/logs/"*)"
same_study "$work/proxy/study-n4-seed21.db" "$work/proxy-reference.db" proxy
same_study "$work/soft/study-n1-seed22.db" "$work/soft-reference.db" soft

# 2. A power point's studies as jobs, analysed after their merge: the power equals the one
# computed here (its timings aside).
"$cli" power --protocol "$protocol" --pipeline --world proxy --n 4,6 --sims 2 --seed 5 \
  --slurm "$work/power" --per-task 2 >/dev/null
"$cli" power --protocol "$protocol" --pipeline --world proxy --n 4,6 --sims 2 --seed 5 --quiet \
  --jobs 2 --json "$work/power-reference.json" >/dev/null
wait_for_jobs "$(jobs_of "$work/power")" 600
[ -s "$work/power/power.json" ] || fail "no power.json: $(cat "$work/power/logs/"*)"
# The JSON without its timings and its note of where the studies ran.
untimed() {
  awk '/"seconds_per_n"/ {skip = 1} skip {if ($0 ~ /\]/) skip = 0; next}
       /"seconds"|pipeline:/ {next} {print}' "$1"
}
cmp -s <(untimed "$work/power/power.json") <(untimed "$work/power-reference.json") ||
  fail "the power from Slurm differs from the one computed here"
echo "power: the power from $(wc -l <"$work/power/tasks.tsv") array tasks equals the one computed here"

# 3. A task cancelled midway: the series stays unfinished, its merge never runs; what is there
# merged by hand is a partial study, reported as one until the task is rerun and the merge
# job merges the rest in.
"$cli" simulate --protocol "$protocol" --participants 4 --seed 23 --world proxy --frames \
  --per-task 2 --slurm "$work/cut" --time 0:10:00 >/dev/null
read -r array merge < <(jobs_of "$work/cut" | tr ',' ' ')
echo "$array $merge" | grep -qE '^[0-9]+ [0-9]+$' || fail "jobs of the cut series: $(cat "$work/cut/jobs.txt")"
# The task's simulate builds its part as PART.tmp.creating and renames it when complete.
for _ in $(seq 1 300); do
  [ -e "$work/cut/parts/n4-seed23/shard-2-of-2.db.tmp.creating" ] && break
  sleep 0.1
done
[ -e "$work/cut/parts/n4-seed23/shard-2-of-2.db.tmp.creating" ] ||
  fail "task 1 never started its part"
scancel "${array}_1"
wait_for_jobs "$array" 600
scancel "$merge" 2>/dev/null || true  # its dependency can no longer be met
status=$("$cli" simulate --status "$work/cut" --json - | tr -d ' \n')
echo "$status" | grep -q '"parts":\["done","stopped"\]' || fail "status after the cancel: $status"
echo "$status" | grep -q '"unfinished_tasks":\[1\]' || fail "status after the cancel: $status"
[ ! -e "$work/cut/study-n4-seed23.db" ] || fail "a study was merged with a part missing"
"$cli" merge --out "$work/cut/study-n4-seed23.db" "$work/cut/parts/n4-seed23/shard-1-of-2.db" \
  >/dev/null 2>&1 && fail "merge accepted one of two parts without --partial"
"$cli" merge --partial --out "$work/cut/study-n4-seed23.db" \
  "$work/cut/parts/n4-seed23/shard-1-of-2.db" >/dev/null
status=$("$cli" simulate --status "$work/cut" --json - | tr -d ' \n')
echo "$status" | grep -q '"merged":false,"merged_partial":true' ||
  fail "status after a partial merge: $status"
echo "$status" | grep -q '"unfinished_tasks":\[1\]' || fail "status after a partial merge: $status"
"$cli" study status --db "$work/cut/study-n4-seed23.db" | grep -q "partial study: 2 of 4" ||
  fail "study status does not say the merged study is partial"
# The rerun as `status` tells it, its JOB the id of the line before.
mapfile -t rerun_lines < <("$cli" simulate --status "$work/cut" | sed -n 's/^  sbatch //p')
[ "${#rerun_lines[@]}" = 2 ] || fail "status's rerun commands: ${rerun_lines[*]}"
rerun=$(eval "sbatch --parsable ${rerun_lines[0]}")
merge=$(eval "sbatch --parsable ${rerun_lines[1]/JOB/$rerun}")
wait_for_jobs "$rerun,$merge" 600
"$cli" simulate --status "$work/cut" | grep -q "every part is done" || fail "the rerun left parts"
status=$("$cli" simulate --status "$work/cut" --json - | tr -d ' \n')
echo "$status" | grep -q '"merged":true,"merged_partial":false' ||
  fail "the merge job did not complete the partial study: $status"
"$cli" simulate --protocol "$protocol" --participants 4 --seed 23 --world proxy --frames --jobs 2 \
  --quiet --db "$work/cut-reference.db" >/dev/null
same_study "$work/cut/study-n4-seed23.db" "$work/cut-reference.db" cut
echo "PASS"
