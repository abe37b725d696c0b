#!/usr/bin/env python3
"""doc-figures.py [--conflicts] [DOC.md ...]

Every figure the docs state (a number with its unit), with the words before it and where it
stands, sorted by unit and those words, so that a figure said in two places sits in one stretch
of the list. --conflicts lists only the figures whose last three words before them are the same
in two places (outside tables) while their values differ: the candidates for a figure said twice
with two values.
Reads docs/*.md and README.md (not their code blocks) by default.
"""
import collections
import glob
import re
import sys

UNITS = (r"ms|s|min|h|mm|cm|m|N|N m|N/m|N/mm|Hz|MB|GB|kB|KiB|MiB|GiB|%|°|kg|g|kPa|MPa|rad|"
         r"m/s|m/s²|cm/s|frames/s|steps|trials|participants|cores|threads")
FIGURE = re.compile(r"(?<![\w.])(\d[\d,]*(?:\.\d+)?)\s?(" + UNITS + r")(?![\w/²])")
WORD = re.compile(r"[a-z][a-z'-]+")
KEY_WORDS = 3
STOP = {"the", "a", "an", "of", "in", "on", "at", "to", "and", "or", "is", "are", "by", "with",
        "for", "its", "it", "as", "from", "than", "about", "each", "every", "one", "that"}


def figures(path):
    """(key, value, place, context, in a table) of each figure in `path` outside code blocks."""
    in_code = False
    for number, line in enumerate(open(path, encoding="utf-8"), 1):
        if line.lstrip().startswith("```"):
            in_code = not in_code
        if in_code:
            continue
        for m in FIGURE.finditer(line):
            before = [w for w in WORD.findall(line[: m.start()].lower()) if w not in STOP]
            if len(before) < 2:
                continue
            key = " ".join(before[-KEY_WORDS:]) + " [" + m.group(2) + "]"
            yield (key, m.group(1).replace(",", ""), f"{path}:{number}", " ".join(before[-8:]),
                   line.lstrip().startswith("|"))


def list_all(found):
    for key, value, where, context, _ in sorted(found, key=lambda f: (f[0].split("[")[-1], f[3])):
        unit = key.split("[")[-1].rstrip("]")
        print(f"{value:>10} {unit:<6} {where:<34} {context}")
    print(f"{len(found)} figures", file=sys.stderr)


def list_conflicts(found):
    # A table's rows are different measurements by design: its cells are left out.
    groups = collections.defaultdict(list)
    for key, value, where, _, in_table in found:
        if not in_table:
            groups[key].append((value, where))
    listed = 0
    for key in sorted(groups):
        if len({v for v, _ in groups[key]}) > 1 and len({w for _, w in groups[key]}) > 1:
            listed += 1
            print(key)
            for value, where in groups[key]:
                print(f"  {value:>10}  {where}")
    print(f"{listed} keys with two values, of {len(groups)}", file=sys.stderr)


def main(argv):
    conflicts = "--conflicts" in argv
    paths = [a for a in argv if a != "--conflicts"]
    paths = paths or sorted(glob.glob("docs/*.md")) + ["README.md"]
    found = [f for path in paths for f in figures(path)]
    (list_conflicts if conflicts else list_all)(found)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
