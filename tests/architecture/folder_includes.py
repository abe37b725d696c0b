#!/usr/bin/env python3
"""The include graph between folders (docs/architecture.md): no loop between the folders of
core/, analysis/ and studies/, and what analyses or exports a finished study (studies/analysis,
studies/export, studies/report, the pilot model) includes neither the session runner nor the
trial driver. Prints each breach and exits 1; exits 0 when there is none.

Usage: folder_includes.py SOURCE_DIR
"""
import os
import re
import sys

INCLUDE = re.compile(r'#include "((?:core|studies|analysis)/[^"]+)"')
RUNNING = ("studies/session/session_runner.h", "studies/session/trial_driver.h")
ANALYSING = ("studies/analysis/", "studies/export/", "studies/report/",
             "studies/power/pilot_model.")


def includes(root):
    """(file, included file) for every project include in core/, analysis/ and studies/."""
    for top in ("core", "analysis", "studies"):
        for folder, _, files in os.walk(os.path.join(root, top)):
            for name in files:
                if name.endswith((".h", ".cpp")):
                    path = os.path.join(folder, name)
                    with open(path, encoding="utf-8") as f:
                        for line in f:
                            m = INCLUDE.match(line)
                            if m:
                                yield os.path.relpath(path, root), m.group(1)


def loops(edges):
    """The strongly connected components of more than one folder (Tarjan)."""
    index, low, stack, on, found, counter = {}, {}, [], set(), [], [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in sorted(edges.get(v, ())):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for v in sorted(edges):
        if v not in index:
            visit(v)
    return found


def main(root):
    edges, breaches = {}, []
    for source, included in includes(root):
        a, b = os.path.dirname(source), os.path.dirname(included)
        if a != b:
            edges.setdefault(a, set()).add(b)
        if source.startswith(ANALYSING) and included in RUNNING:
            breaches.append(f"{source} includes {included}")
    breaches += ["folders include each other: " + " <-> ".join(c) for c in loops(edges)]
    for b in breaches:
        print(b)
    return 1 if breaches else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
