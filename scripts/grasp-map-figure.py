#!/usr/bin/env python3
"""The grasp map as a figure: `sim grasp --json` outputs drawn as SVG (docs/simulator.md).

Usage: scripts/grasp-map-figure.py MAP.json [MAP.json ...] --out FIGURE.svg

Each cube of the maps gets a panel: a row per factor, a cell per level, green where the cube
was held, red where it was lost, amber where it was held in some of a map's repeats (how many
of how many written under the level); below them whether the scripted pinch held, how many
pairs of factors held, and the hold rate over the draws of people's closings with its 95 %
interval. Maps of one cube from several files (a single-factor grid, a run of draws) are
merged. Standard library only.
"""
import argparse
import json
from xml.sax.saxutils import escape

CELL, GAP, LABEL, TOP = 34, 3, 160, 62
HELD, LOST, SOME = "#3f9f5f", "#c8463c", "#d08c1e"


def merged_cubes(paths):
    cubes, factors = {}, []
    for path in paths:
        with open(path, encoding="utf-8") as f:
            doc = json.load(f)
        factors = factors or doc["factors"]
        for cube in doc["cubes"]:
            entry = cubes.setdefault(cube["cube_size_m"], {"closings": [], "draws": None})
            entry["closings"] += [c for c in cube["closings"] if c["factor"] != "draw"]
            if cube.get("draws", {}).get("run"):
                entry["draws"] = cube["draws"]
    return cubes, factors


def panel(x0, size, cube, factors):
    out = [f'<text x="{x0}" y="{TOP - 12}" font-size="15" font-weight="bold">'
           f'{size * 100:.0f} cm cube</text>']
    single = {}  # (factor, level): held in each repeat
    for c in cube["closings"]:
        if c["factor"] not in ("", "pair", "closing"):
            single.setdefault((c["factor"], round(c["level"], 6)), []).append(c["held"])
    pinch = [c["held"] for c in cube["closings"] if c["factor"] == ""]
    y = TOP
    for f in factors:
        if not any(k[0] == f["name"] for k in single):
            continue
        out.append(f'<text x="{x0}" y="{y + CELL * 0.62}" font-size="12">'
                   f'{escape(f["name"])} ({escape(f["unit"])})</text>')
        for i, level in enumerate(f["levels"]):
            held = single.get((f["name"], round(level, 6)), [])
            x = x0 + LABEL + i * (CELL + GAP)
            some = 0 < sum(held) < len(held)
            fill = ("#cccccc" if not held else HELD if all(held) else SOME if some else LOST)
            out.append(f'<rect x="{x}" y="{y}" width="{CELL}" height="{CELL}" fill="{fill}"/>')
            out.append(f'<text x="{x + CELL / 2}" y="{y + CELL * (0.48 if some else 0.62)}" '
                       f'font-size="10" text-anchor="middle" fill="white">{level:g}</text>')
            if some:
                out.append(f'<text x="{x + CELL / 2}" y="{y + CELL * 0.86}" font-size="8" '
                           f'text-anchor="middle" fill="white">{sum(held)}/{len(held)}</text>')
        y += CELL + GAP
    if pinch:
        said = ("held" if all(pinch) else "lost" if not any(pinch) else
                f"held in {sum(pinch)} of {len(pinch)} repeats")
        out.append(f'<text x="{x0}" y="{y + 16}" font-size="12">the scripted pinch: '
                   f'{said}</text>')
        y += 22
    pairs = [c for c in cube["closings"] if c["factor"] == "pair"]
    if pairs:
        held = sum(c["held"] for c in pairs)
        out.append(f'<text x="{x0}" y="{y + 16}" font-size="12">pairs of factors: '
                   f'{held} of {len(pairs)} runs held</text>')
        y += 22
    d = cube["draws"]
    if d:
        w = 9 * (CELL + GAP)
        bx = x0 + LABEL
        out.append(f'<text x="{x0}" y="{y + 16}" font-size="12">people\'s closings</text>')
        out.append(f'<rect x="{bx}" y="{y + 4}" width="{w}" height="16" fill="#eeeeee"/>')
        out.append(f'<rect x="{bx}" y="{y + 4}" width="{w * d["hold_rate"]:.1f}" height="16" '
                   f'fill="{HELD}"/>')
        lo, hi = bx + w * d["hold_rate_low"], bx + w * d["hold_rate_high"]
        out.append(f'<line x1="{lo:.1f}" y1="{y + 12}" x2="{hi:.1f}" y2="{y + 12}" '
                   f'stroke="black" stroke-width="2"/>')
        out.append(f'<line x1="{bx + w * 0.95:.1f}" y1="{y}" x2="{bx + w * 0.95:.1f}" '
                   f'y2="{y + 24}" stroke="black" stroke-dasharray="3,2"/>')
        out.append(f'<text x="{x0}" y="{y + 38}" font-size="11">held {d["held"]} of '
                   f'{d["run"]} ({100 * d["hold_rate"]:.0f} %, 95 % CI '
                   f'{100 * d["hold_rate_low"]:.0f}-{100 * d["hold_rate_high"]:.0f} %); '
                   f'dashed: the 95 % target</text>')
        y += 44
    return out, y


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("maps", nargs="+")
    parser.add_argument("--out", required=True)
    parser.add_argument("--title", default="")
    args = parser.parse_args()
    cubes, factors = merged_cubes(args.maps)
    width = LABEL + 9 * (CELL + GAP) + 30
    body, height = [], 0
    for k, size in enumerate(sorted(cubes)):
        part, bottom = panel(10 + k * width, size, cubes[size], factors)
        body += part
        height = max(height, bottom)
    title = f'<text x="10" y="18" font-size="13">{escape(args.title)}</text>' if args.title else ""
    svg = (f'<svg xmlns="http://www.w3.org/2000/svg" width="{width * len(cubes) + 10}" '
           f'height="{height + 10}" font-family="DejaVu Sans, sans-serif">'
           f'<rect width="100%" height="100%" fill="white"/>{title}{"".join(body)}</svg>\n')
    with open(args.out, "w", encoding="utf-8") as f:
        f.write(svg)


if __name__ == "__main__":
    main()
