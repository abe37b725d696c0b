#!/usr/bin/env python3
"""The planning table of docs/cluster.md: what a simulated study, a series and a power point
cost on a cluster, projected from measured participants.

    scripts/cluster-plan.py STUDY.db...

Each simulated participant's time is its session's (ended_at - started_at), a participant
being one array task on one core. The projection draws participants from that distribution
(with replacement: 400 times for a study or a series, 20 times for a power point's 20,000)
and deals them to C cores as Slurm deals array tasks, each to
the first core that is free; a study waits for its slowest participant, a series for its
last. Prints the distribution and the median (and 90th percentile) wall time per case.
Python's standard library only."""
import random
import sqlite3
import statistics
import sys


def durations(paths):
    out = []
    for path in paths:
        db = sqlite3.connect(f"file:{path}?mode=ro", uri=True)
        rows = db.execute(
            "SELECT (julianday(ended_at) - julianday(started_at)) * 86400 FROM session "
            "WHERE ended_at IS NOT NULL AND status = 'finished'").fetchall()
        out += [r[0] for r in rows]
        db.close()
    return sorted(out)


def makespan(tasks, cores):
    free = [0.0] * min(cores, len(tasks))
    for t in tasks:  # in submission order, each to the core free first
        i = free.index(min(free))
        free[i] += t
    return max(free)


def quantile(xs, q):
    xs = sorted(xs)
    return xs[min(len(xs) - 1, int(q * len(xs)))]


def hours(s):
    return f"{s / 60:.1f} min" if s < 5400 else f"{s / 3600:.1f} h"


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    d = durations(sys.argv[1:])
    print(f"{len(d)} participants: min {d[0]:.0f} s, median {statistics.median(d):.0f} s, "
          f"mean {statistics.mean(d):.0f} s, 90th percentile {quantile(d, 0.9):.0f} s, "
          f"max {d[-1]:.0f} s; total {sum(d) / 3600:.1f} h")
    rng = random.Random(2021)
    cases = [("one N = 20 study", 20), ("ten N = 20 studies", 200),
             ("a power point: 1,000 studies of N = 20", 20000)]
    print("| | " + " | ".join(f"{c} cores" for c in (1, 20, 100, 400)) + " |")
    print("|---|" + "---|" * 4)
    for name, n in cases:
        cells = []
        for cores in (1, 20, 100, 400):
            spans = [makespan([rng.choice(d) for _ in range(n)], cores)
                     for _ in range(400 if n <= 200 else 20)]
            cells.append(f"{hours(statistics.median(spans))} ({hours(quantile(spans, 0.9))})")
        print(f"| {name} | " + " | ".join(cells) + " |")


main()
