#!/usr/bin/python3
"""Charts of shadowlab benchmark results (the JSON or CSV written by `shadowlab bench`).

    python3 tools/charts.py results.json OUT_DIR

Writes PNG files into OUT_DIR:
  pareto-<scene>-<WxH>-<hard|soft>.png         error against GPU milliseconds, one point per (technique, parameters),
                              the Pareto front drawn (lower left is better)
  sweep-<key>-<scene>.png     milliseconds against each swept parameter (shadow-map resolution,
                              kernel sizes, light size, ...): the sweeps of seed 000 Fig. 4.1-4.11
  resolution-<scene>.png      milliseconds against output resolution (pixels)
  triangles.png               milliseconds against triangle count
and prints the file names. Needs python3-matplotlib only.
"""
import csv
import json
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

FRAME = "gpu_frame_ms"
TECHNIQUE_MS = "gpu_technique_ms"


def load(path):
    if path.endswith(".csv"):
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
        for row in rows:
            for key, value in list(row.items()):
                if value == "":
                    del row[key]
                    continue
                try:
                    row[key] = float(value)
                except ValueError:
                    pass
        return rows
    with open(path) as f:
        return json.load(f)


def number(value):
    try:
        return float(value)
    except (TypeError, ValueError):
        return None


def label(row, varying):
    parts = [row["technique"]]
    parts += [f"{k.split('.', 1)[1]}={row[k]}" for k in varying if k in row]
    return " ".join(parts)


def pareto_front(points):
    """Points (ms, error) not dominated by any other: sorted by ms, strictly falling error."""
    front, best = [], float("inf")
    for ms, err in sorted(points):
        if err < best:
            front.append((ms, err))
            best = err
    return front


def varying_keys(rows, prefix):
    values = defaultdict(set)
    for row in rows:
        for key, value in row.items():
            if key.startswith(prefix):
                values[key].add(str(value))
    return sorted(k for k, v in values.items() if len(v) > 1)


def chart_pareto(rows, scene, out_dir, size_name, error_key):
    rows = [r for r in rows if error_key in r and FRAME in r]
    if not rows:
        return None
    varying = varying_keys(rows, "param.")
    fig, ax = plt.subplots(figsize=(9, 6))
    by_technique = defaultdict(list)
    for row in rows:
        by_technique[row["technique"]].append(row)
    colours = plt.get_cmap("tab20").colors
    for index, (technique, items) in enumerate(sorted(by_technique.items())):
        ax.scatter([r[FRAME] for r in items], [r[error_key] for r in items], label=technique, s=28,
                   color=colours[(2 * index) % 20 + (index // 10)], marker="osD^vPX*h<>"[index % 11])
    front = pareto_front([(r[FRAME], r[error_key]) for r in rows])
    ax.plot([p[0] for p in front], [p[1] for p in front], "k--", lw=1, label="Pareto front")
    for row in rows:
        if (row[FRAME], row[error_key]) in front:
            ax.annotate(label(row, varying), (row[FRAME], row[error_key]), fontsize=6, xytext=(3, 3),
                        textcoords="offset points")
    reference = "soft" if error_key.startswith("soft") else "hard"
    ax.set_xlabel("GPU milliseconds per frame (median)")
    ax.set_ylabel(f"mean absolute visibility error vs {reference} reference")
    ax.set_title(f"Speed against accuracy: {scene} at {size_name} ({rows[0].get('gpu', '')})", fontsize=9)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    path = os.path.join(out_dir, f"pareto-{scene}-{size_name}-{reference}.png")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def follows(rows, key, other):
    """True when `other` is a function of `key` over rows (swept together, like a radius with a grid)."""
    seen = {}
    for row in rows:
        if key in row:
            value = str(row.get(other))
            if seen.setdefault(str(row[key]), value) != value:
                return False
    return len(seen) > 1


def chart_against(rows, key, scene, out_dir, xlabel, name, logx=False):
    series = defaultdict(list)
    by_technique = defaultdict(list)
    for row in rows:
        by_technique[row["technique"]].append(row)
    linked = {t: {k for r in items for k in r if k != key and (k.startswith("param.") or k.startswith("scene."))
                  and follows(items, key, k)} for t, items in by_technique.items()}
    for row in rows:
        x = number(row.get(key))
        if x is None or FRAME not in row:
            continue
        others = tuple(sorted((k, str(v)) for k, v in row.items()
                              if (k.startswith("param.") or k.startswith("scene.")) and k != key
                              and k not in linked[row["technique"]]))
        size = (None, None) if key == "pixels" else (row.get("width"), row.get("height"))
        series[(row["technique"], *size, others)].append(
            (x, row[FRAME], row.get(TECHNIQUE_MS, 0.0)))
    series = {k: sorted(v) for k, v in series.items() if len({p[0] for p in v}) > 1}
    if not series:
        return None
    fig, ax = plt.subplots(figsize=(9, 6))
    for (technique, width, height, others), points in sorted(series.items(), key=lambda kv: str(kv[0])):
        extra = f" {int(width)}x{int(height)}" if width else ""
        ax.plot([p[0] for p in points], [p[1] for p in points], marker="o", ms=3, label=technique + extra)
    ax.set_xlabel(xlabel)
    ax.set_ylabel("GPU milliseconds per frame (median)")
    if logx:
        ax.set_xscale("log", base=2)
    ax.set_title(f"{scene}: frame time against {xlabel}", fontsize=9)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=6, ncol=2)
    path = os.path.join(out_dir, f"{name}-{scene}.png")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def main(argv):
    if len(argv) != 3:
        print(__doc__)
        return 2
    rows = [r for r in load(argv[1]) if r.get("technique") and r.get("technique") != "depth-floor"]
    out_dir = argv[2]
    os.makedirs(out_dir, exist_ok=True)
    written = []
    scenes = sorted({r["scene"] for r in rows})
    for scene in scenes:
        scene_rows = [r for r in rows if r["scene"] == scene]
        for size in sorted({(int(r["width"]), int(r["height"])) for r in scene_rows if "width" in r}):
            sized = [r for r in scene_rows if (int(r.get("width", 0)), int(r.get("height", 0))) == size]
            for error_key in ("hard_mae", "soft_mae"):
                written.append(chart_pareto(sized, scene, out_dir, f"{size[0]}x{size[1]}", error_key))
        for key in varying_keys(scene_rows, "param.") + (["light_size"] if len({r.get("light_size") for r in scene_rows}) > 1 else []):
            name = "sweep-" + key.replace("param.", "").replace("_", "-")
            written.append(chart_against(scene_rows, key, scene, out_dir, key.replace("param.", ""), name,
                                         logx=key == "param.resolution"))
        written.append(chart_against(scene_rows, "pixels", scene, out_dir, "output pixels", "resolution"))
    by_triangles = [r for r in rows if number(r.get("triangles"))]
    if len({r["triangles"] for r in by_triangles}) > 1:
        written.append(chart_against(by_triangles, "triangles", "all", out_dir, "triangles", "triangles"))
    for path in written:
        if path:
            print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
