#!/usr/bin/env bash
# Runs K simulated N-participant studies of the ISMAR 2021 protocol on the soft hand (seeds
# FIRST, FIRST+1, ...), analyses each as `analyze --db` does, and prints one row a study with
# the statistics the paper reports (docs/simulated-participants.md, "Ten simulated studies").
# A study already in OUT is analysed again, not rerun. Needs python3 for the summary.
#   scripts/simulated-studies.sh [K=10] [N=20] [FIRST=1] [OUT=build/simulated-studies]
set -euo pipefail
cd "$(dirname "$0")/.."
k=${1:-10} n=${2:-20} first=${3:-1} out=${4:-build/simulated-studies}
command -v python3 >/dev/null || { echo "simulated-studies.sh: needs python3" >&2; exit 1; }
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build --target handlab-cli -j "$(nproc)" >/dev/null
mkdir -p "$out"
for ((s = first; s < first + k; ++s)); do
  db="$out/study-n$n-seed$s.db"
  [ -f "$db" ] || build/app/handlab-cli simulate --protocol studies/fine-manipulation-2021.json \
    --participants "$n" --seed "$s" --db "$db" --json "$out/study-n$n-seed$s.simulate.json"
  build/app/handlab-cli analyze --db "$db" --json "$out/study-n$n-seed$s.analysis.json" >/dev/null
done
python3 - "$out" "$n" "$first" "$k" <<'PY'
import json, sys
out, n, first, k = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4])
def fmt(x, d=2): return "NA" if x is None else f"{x:.{d}f}"
print("| seed | success ours gross / fine | naive gross / fine | MxS F | p | fine naive-ours t | p (Tukey) | gross p (Tukey) | repetition F | p (GG) | Friedman precision / ease / naturalness |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
for s in range(first, first + k):
    sim = json.load(open(f"{out}/study-n{n}-seed{s}.simulate.json"))
    rate = {c["condition"]: c["success_rate"] for c in sim["conditions"]}
    a = json.load(open(f"{out}/study-n{n}-seed{s}.analysis.json"))
    ct = a["completion_time"]
    eff = {e["effect"]: e for e in ct["anova"]}
    mxs = eff.get("strategy:manipulation", {})
    rep = eff.get("repetition", {})
    ph = {}
    for p in ct["posthoc"]:
        if p["effect"] == "strategy:manipulation" and not p["by"]:
            ph[frozenset(p["contrast"].split(" - "))] = p
    fine = ph.get(frozenset(["naive fine", "ours fine"]), {})
    gross = ph.get(frozenset(["naive gross", "ours gross"]), {})
    t = fine.get("t")
    if t is not None and fine["contrast"].startswith("ours"): t = -t
    fr = {f["dv"]: f["chisq"] for f in a["questionnaire"]["friedman"]}
    print(f"| {s} | {rate.get('ours-gross', 0):.0%} / {rate.get('ours-fine', 0):.0%} "
          f"| {rate.get('naive-gross', 0):.0%} / {rate.get('naive-fine', 0):.0%} "
          f"| {fmt(mxs.get('F'))} | {fmt(mxs.get('p'), 3)} | {fmt(t)} | {fmt(fine.get('p_tukey'), 3)} "
          f"| {fmt(gross.get('p_tukey'), 3)} | {fmt(rep.get('F'))} | {fmt(rep.get('p_gg'), 3)} "
          f"| {fmt(fr.get('precision'))} / {fmt(fr.get('ease'))} / {fmt(fr.get('naturalness'))} |")
PY
