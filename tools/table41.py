#!/usr/bin/python3
"""Rebuilds seed 000 Table 4.1 (visual characteristics of the techniques) from measurements.

    python3 tools/table41.py seed000.json [more.json ...] [--out DIR]

Input: results of `shadowlab bench --spec assets/bench/seed000.json` (rows tagged table41-*), JSON
or CSV, read with tools/results.py; when several files hold a row, the first file's is used.
Without --out the Markdown table goes to stdout; with it, to DIR/table41.md (the path is printed).
Each characteristic is a measured criterion on one scene, judged against plain shadow mapping
in the same run, so the thresholds travel between machines:

  Precise shadows   (dragon-like)  error away from the hard reference's edges, hard_mae_outside_penumbra:
                                   Yes <= 2x shadowmap + 0.0005, ~ <= 5x, else No
  Soft shadows      (contact)      share of pixels the technique draws as penumbra:
                                   Yes >= 3x shadowmap and >= 0.3x area-reference, ~ >= 1.5x shadowmap
  Anti-aliasing     (cube, 512 map) high-frequency error against the hard reference (staircase):
                                   Yes <= 0.5x shadowmap, ~ <= 0.85x
  Contact hardening (hover)        penumbra share with the sphere 1.5 above the ground / touching it:
                                   Yes >= 1.5 (and a penumbra at all), ~ >= 1.2
  Surface acne-free (pillars, 15 degree sun) false-shadow rate against the hard reference:
                                   Yes <= 0.1%, ~ <= 0.5%
  Noise-free        (contact)      high-frequency error against the soft reference:
                                   Yes <= 1.5x shadowmap, ~ <= 3x
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import results  # noqa: E402

COLUMNS = [("shadowmap", "Shadow mapping", False), ("shadowmap", "HW filtering", True), ("pcf", "PCF", None),
           ("adaptive-pcf", "Adaptive PCF", None), ("vsm", "VSM", None), ("pcss", "PCSS", None),
           ("esm", "ESM", None), ("evsm", "EVSM", None), ("msm", "MSM", None), ("area-reference", "Area reference", None)]
SEED = {"Precise shadows": ["Yes", "Yes", "Yes", "Yes", "~", "Yes"],
        "Soft shadows": ["No", "No", "Yes", "Yes", "Yes", "Yes"],
        "Anti-aliasing": ["No", "~", "~", "Yes", "Yes", "Yes"],
        "Contact-hardening shadows": ["No", "No", "No", "No", "No", "Yes"],
        "Surface acne-free": ["No", "No", "No", "No", "Yes", "No"],
        "Noise-free": ["Yes", "Yes", "Yes", "No", "No", "No"]}


def scene_value(row, key):
    value = results.number(row.get(key))
    return -1.0 if value is None else value


def pick(rows, tag, technique, hardware, **scene):
    """The first row of sweep table41-<tag> for the column: shadowmap with hardware filtering
    (hardware True), without it (False or None), any other technique as is; scene: scene.* values."""
    for row in rows:
        if row.get("spec") != "table41-" + tag or row.get("technique") != technique:
            continue
        filtered = results.canonical(row.get("param.hardware_filter")) == "true"
        if technique == "shadowmap" and hardware is not None and filtered != hardware:
            continue
        if technique == "shadowmap" and hardware is None and filtered:
            continue
        if all(abs(scene_value(row, k) - v) < 1e-6 for k, v in scene.items()):
            return row
    return None


def grade(value, yes, partial, lower_is_better=True):
    if value is None:
        return "n/a"
    good = (lambda a, b: a <= b) if lower_is_better else (lambda a, b: a >= b)
    return "Yes" if good(value, yes) else "~" if good(value, partial) else "No"


def table(rows):
    """The Markdown table (a string) of rows (results.load)."""
    base = lambda tag, key, **s: (pick(rows, tag, "shadowmap", False, **s) or {}).get(key)
    verdicts = {}
    for technique, name, hardware in COLUMNS:
        cells = {}
        r = pick(rows, "precise", technique, hardware)
        v, b = (r or {}).get("hard_mae_outside_penumbra"), base("precise", "hard_mae_outside_penumbra")
        cells["Precise shadows"] = (grade(v, 2 * b + 0.0005, 5 * b + 0.0005) if v is not None and b is not None else "n/a", v)
        r = pick(rows, "soft", technique, hardware)
        v, b = (r or {}).get("technique_penumbra_fraction"), base("soft", "technique_penumbra_fraction")
        area = (pick(rows, "soft", "area-reference", None) or {}).get("technique_penumbra_fraction", 0.0)
        if v is None or b is None:
            cells["Soft shadows"] = ("n/a", v)
        else:
            cells["Soft shadows"] = ("Yes" if v >= 3 * b and v >= 0.3 * area else "~" if v >= 1.5 * b and v > 0.0005 else "No", v)
        r = pick(rows, "aliasing", technique, hardware)
        v, b = (r or {}).get("hard_noise"), base("aliasing", "hard_noise")
        cells["Anti-aliasing"] = (grade(v, 0.5 * b, 0.85 * b) if v is not None and b else "n/a", v)
        low = (pick(rows, "contact", technique, hardware, **{"scene.height": 0.5}) or {}).get("technique_penumbra_fraction")
        high = (pick(rows, "contact", technique, hardware, **{"scene.height": 2.0}) or {}).get("technique_penumbra_fraction")
        if low is None or high is None:
            cells["Contact-hardening shadows"] = ("n/a", None)
        else:
            ratio = high / low if low > 1e-6 else (float("inf") if high > 1e-4 else 1.0)
            yes = ratio >= 1.5 and high > 1e-3
            cells["Contact-hardening shadows"] = ("Yes" if yes else "~" if ratio >= 1.2 and high > 1e-3 else "No", ratio)
        r = pick(rows, "grazing", technique, hardware)
        v = (r or {}).get("hard_false_shadow")
        cells["Surface acne-free"] = (grade(v, 0.001, 0.005), v)
        r = pick(rows, "soft", technique, hardware)
        v, b = (r or {}).get("soft_noise"), base("soft", "soft_noise")
        cells["Noise-free"] = (grade(v, 1.5 * b, 3 * b) if v is not None and b else "n/a", v)
        verdicts[name] = cells

    names = [name for _, name, _ in COLUMNS]
    out = ["| characteristic (measured) | " + " | ".join(names) + " |", "|---|" + "---|" * len(names)]
    for characteristic in SEED:
        cells = []
        for name in names:
            verdict, value = verdicts[name][characteristic]
            cells.append(verdict + (f" ({value:.3g})" if isinstance(value, float) else ""))
        out.append(f"| {characteristic} | " + " | ".join(cells) + " |")
        out.append("| *seed 000* | " + " | ".join(SEED[characteristic] + [""] * (len(names) - 6)) + " |")
    return "\n".join(out) + "\n"


def main(argv=None):
    parser = argparse.ArgumentParser(prog="table41.py", description="Seed 000 Table 4.1 rebuilt from the "
                                     "table41-* rows of shadowlab bench results (Markdown).")
    parser.add_argument("inputs", nargs="+", metavar="RESULTS", help="results files (.json or .csv)")
    parser.add_argument("--out", metavar="DIR", help="write DIR/table41.md instead of printing")
    args = parser.parse_args(sys.argv[1:] if argv is None else argv)
    try:
        rows = results.load(args.inputs)
    except (OSError, ValueError) as e:
        print(f"table41.py: {e}", file=sys.stderr)
        return 1
    if not any(str(r.get("spec", "")).startswith("table41-") for r in rows):
        print("table41.py: no table41-* rows (run shadowlab bench --spec assets/bench/seed000.json)", file=sys.stderr)
        return 1
    text = table(rows)
    if args.out:
        print(results.write_text(text, args.out, "table41.md"))
    else:
        sys.stdout.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
