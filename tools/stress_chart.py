#!/usr/bin/python3
"""Chart of a shadowlab stress run (the results.json written by `shadowlab stress`).

    python3 tools/stress_chart.py results.json --out OUT_DIR [--dpi 120]

Writes OUT_DIR/stress.png and prints its path: a grid of technique (rows) x case (columns), each
cell coloured by its verdict (green pass, magenta fail, grey skipped), with the measured value, the
value as a multiple of the case's threshold, and whether the verdict agrees with the literature's
claim for that technique (the `expectedToFail` / `expectedToPass` lists of assets/stress/cases.json,
the `expected_to_fail` / `expected_to_pass` fields of each row), with the same marks as the README
table: "as claimed" when a technique named as failing fails, one named as doing better passes, or
the reference passes; "claim: fails" when a technique named as failing passes; "claim: passes"
when one named as doing better fails; nothing where the claim names neither. Cells the claim names
are framed: solid where it says the technique fails, dashed where it says it does better; black
when the measurement agrees, a thick orange frame when it does not. The title counts the
agreements. Needs python3-matplotlib.
"""
import argparse
import json
import os
import sys
import textwrap

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Rectangle  # noqa: E402

PASS, FAIL, SKIPPED = "#7fc97f", "#f0027f", "#cccccc"
AGREES, DISAGREES = "black", "#ff7f00"


def claim_mark(row):
    """The README's mark for one row: (text, agrees) with agrees True, False or None (no claim)."""
    if row.get("skipped"):
        return "", None
    passed = bool(row["pass"])
    if row.get("expected_to_fail"):
        return ("claim: fails", False) if passed else ("as claimed", True)
    if row.get("expected_to_pass"):
        return ("as claimed", True) if passed else ("claim: passes", False)
    if row["technique"] == "reference" and passed:
        return "as claimed", True
    return "", None


def draw(rows):
    """The figure and, per (technique, case), what was drawn: colour, text and frame (for the tests)."""
    cases, techniques = [], []
    for row in rows:
        if row["case"] not in cases:
            cases.append(row["case"])
        if row["technique"] not in techniques:
            techniques.append(row["technique"])
    cell = {(r["technique"], r["case"]): r for r in rows}
    drawn = {}
    agree = disagree = 0
    fig, ax = plt.subplots(figsize=(1.0 + 0.95 * len(cases), 0.9 + 0.5 * len(techniques)))
    for y, technique in enumerate(techniques):
        for x, case in enumerate(cases):
            row = cell.get((technique, case))
            if row is None:
                continue
            mark, agrees = claim_mark(row)
            if row.get("skipped"):
                colour, text = SKIPPED, "skipped"
            else:
                colour = PASS if row["pass"] else FAIL
                ratio = row["value"] / row["threshold"] if row["threshold"] > 0 else float("inf")
                text = "%.3g\n%.2gx" % (row["value"], ratio)
                if mark:
                    text += "\n" + mark
            ax.add_patch(Rectangle((x, y), 1, 1, facecolor=colour, edgecolor="white", linewidth=1.5))
            frame = None
            if agrees is not None and technique != "reference":
                frame = {
                    "colour": AGREES if agrees else DISAGREES,
                    "style": "solid" if row.get("expected_to_fail") else "dashed",
                }
                ax.add_patch(Rectangle((x + 0.06, y + 0.06), 0.88, 0.88, fill=False, edgecolor=frame["colour"],
                                       linestyle=frame["style"], linewidth=1.2 if agrees else 2.4))
            if agrees is True and technique != "reference":
                agree += 1
            elif agrees is False:
                disagree += 1
            ax.text(x + 0.5, y + 0.5, text, ha="center", va="center", fontsize=6.0)
            drawn[(technique, case)] = {"colour": colour, "text": text, "mark": mark, "agrees": agrees, "frame": frame}
    ax.set_xlim(0, len(cases))
    ax.set_ylim(len(techniques), 0)
    ax.set_xticks([i + 0.5 for i in range(len(cases))])
    ax.set_xticklabels(cases, rotation=45, ha="right", fontsize=7)
    ax.set_yticks([i + 0.5 for i in range(len(techniques))])
    ax.set_yticklabels(techniques, fontsize=7)
    legend = ("stress: value, multiple of the threshold and the claim (green pass, magenta fail; framed where the "
              "literature names the technique: solid fails, dashed does better; orange: the measurement disagrees)")
    # Wrapped to the grid's width (about 14 characters a column at this font size).
    title = "\n".join(textwrap.wrap(legend, width=max(50, 14 * len(cases))))
    title += "\n%d of %d cells the claims name agree with them" % (agree, agree + disagree)
    ax.set_title(title, fontsize=7)
    ax.tick_params(length=0)
    for side in ax.spines.values():
        side.set_visible(False)
    fig.tight_layout()
    return fig, drawn, (agree, disagree)


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
    fig, _, _ = draw(rows)
    os.makedirs(args.out, exist_ok=True)
    out = os.path.join(args.out, "stress.png")
    fig.savefig(out, dpi=args.dpi)
    plt.close(fig)
    print(out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
