#!/usr/bin/python3
"""Chart of a shadowlab stress run (the results.json written by `shadowlab stress`).

    python3 tools/stress_chart.py results.json --out OUT_DIR [--dpi 120]

Writes OUT_DIR/stress.png and prints its path: a grid of technique (rows) x case (columns), each
cell coloured by its verdict (green pass, red fail, grey skipped), with the measured value and the
value as a multiple of the case's threshold; a cell whose technique the literature expects to fail
there has a black frame. Needs python3-matplotlib.
"""
import argparse
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Rectangle  # noqa: E402


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("results", help="results.json of `shadowlab stress`")
    parser.add_argument("--out", required=True, help="folder for stress.png")
    parser.add_argument("--dpi", type=int, default=120)
    args = parser.parse_args(argv)
    with open(args.results) as f:
        rows = json.load(f)
    if not rows:
        print("stress_chart.py: no rows in " + args.results, file=sys.stderr)
        return 1
    cases, techniques = [], []
    for row in rows:
        if row["case"] not in cases:
            cases.append(row["case"])
        if row["technique"] not in techniques:
            techniques.append(row["technique"])
    cell = {(r["technique"], r["case"]): r for r in rows}
    fig, ax = plt.subplots(figsize=(1.0 + 0.9 * len(cases), 0.9 + 0.42 * len(techniques)))
    for y, technique in enumerate(techniques):
        for x, case in enumerate(cases):
            row = cell.get((technique, case))
            if row is None:
                continue
            if row.get("skipped"):
                colour, text = "#cccccc", "skipped"
            else:
                colour = "#7fc97f" if row["pass"] else "#f0027f"
                ratio = row["value"] / row["threshold"] if row["threshold"] > 0 else float("inf")
                text = "%.3g\n%.2gx" % (row["value"], ratio)
            ax.add_patch(Rectangle((x, y), 1, 1, facecolor=colour, edgecolor="white", linewidth=1.5))
            if row.get("expected_to_fail"):
                ax.add_patch(Rectangle((x + 0.06, y + 0.06), 0.88, 0.88, fill=False, edgecolor="black", linewidth=1.2))
            ax.text(x + 0.5, y + 0.5, text, ha="center", va="center", fontsize=6.5)
    ax.set_xlim(0, len(cases))
    ax.set_ylim(len(techniques), 0)
    ax.set_xticks([i + 0.5 for i in range(len(cases))])
    ax.set_xticklabels(cases, rotation=45, ha="right", fontsize=7)
    ax.set_yticks([i + 0.5 for i in range(len(techniques))])
    ax.set_yticklabels(techniques, fontsize=7)
    ax.set_title("stress: value and multiple of the threshold (green pass, magenta fail; framed: the literature expects a failure)",
                 fontsize=8)
    ax.tick_params(length=0)
    for side in ax.spines.values():
        side.set_visible(False)
    fig.tight_layout()
    os.makedirs(args.out, exist_ok=True)
    out = os.path.join(args.out, "stress.png")
    fig.savefig(out, dpi=args.dpi)
    print(out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
