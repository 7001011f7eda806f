#!/usr/bin/python3
"""Charts of shadowlab benchmark results (the JSON or CSV written by `shadowlab bench`).

    python3 tools/charts.py results.json [more.json ...] --out OUT_DIR [--dpi 120]
    python3 tools/charts.py results.json OUT_DIR          (the older form; shadowlab report uses it)

Writes PNG files into OUT_DIR and prints their paths, one a line:

  pareto-<scene>-<WxH>-hard.png   error against the hard reference (whole image) against GPU ms per
                                  frame, one point per (technique, parameters)
  pareto-<scene>-<WxH>-soft.png   the same against the soft reference, inside its penumbra
                                  (soft_mae_penumbra: the whole-image soft MAE is diluted by the lit
                                  and fully shadowed pixels); the soft reference's own sampling error
                                  (soft_reference_floor), when the rows carry it, is a grey band
  sweep-<key>-<scene>.png         GPU ms per frame against each swept technique parameter (shadow-map
                                  resolution, kernel sizes, ...) and the light size
  resolution-<scene>.png          GPU ms per frame against output resolution (pixels)
  triangles-<scene>.png           GPU ms per frame against triangle count, one line per technique,
                                  for a sweep of one scene's `scene.*` parameter (scene.count,
                                  scene.segments): only that sweep's rows, never a mix of scenes;
                                  -<WxH> and -<file> are added when a scene was swept at several
                                  sizes or in several files (each file is one run)
  seed001-quads.png               seed 001 Figs. 5.3.A-E: GPU ms per frame against translucent quads
                                  (0-2000), the seed001-timing techniques (cssm2 9x9 and 3x3 two
                                  lines) and composited-translucent's seed001-composited-coarse rows
  seed001-composited-fine.png     seed 001 Fig. 5.3.F: GPU ms per frame against 0-30 quads
                                  (seed001-composited-fine), and composited-translucent's per-quad
                                  loop (translucent_draws_ms) dashed. Both take the rows of every
                                  file given (seed001.json and seed001-composited.json are two
                                  runs; a curve is one file's, labelled [file] when two files
                                  have it) and draw 16.7 and 33.3 ms (60 and 30 Hz) dotted where
                                  the curves cross them

On every chart a technique has the colour and marker of results.STYLE. An axis is logarithmic
when its values span more than a factor of 10. On the Pareto charts `none` is a pair of reference
lines (its time and its error), not a point; the Pareto front is a dashed line and each of its
points is labelled with its technique and the parameters that vary on the chart. Charts of rows
measured with the accuracy G-buffer written on every frame (files from before `frame_ms`) say so
in their title, and so do charts whose rows come from more than one file. The `depth-floor` rows
appear only on the triangles charts (dashed, the depth-only pass).

Legends sit in the right margin, outside the axes (the axes narrowed to make room), so they never
cover a point. The labels of the Pareto front are placed by place_labels(): each at the first of a
ring of positions around its point, nearest first, whose box overlaps no marker of the chart, no
label already placed and stays inside the axes; a label moved away from its point gets a thin
leader line. Beside each PNG, <name>.boxes.json records in pixels of that PNG (origin at the lower
left) the axes, the legend, every label with its anchor and every marker's box; box_problems()
checks them (no label over a marker or another label, the legend off the axes), as the tests do.
Needs python3-matplotlib.
"""
import argparse
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import results  # noqa: E402

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib import ticker  # noqa: E402
from matplotlib.text import Text  # noqa: E402

X = "frame_ms"
LINESTYLES = ("-", "--", ":", "-.")
NOT_CHARTED = ("depth-floor",)   # a floor, not a technique: drawn only where it is the floor


def set_scale(ax, axis, values, base=10):
    """Log scale (results.use_log) on 'x' or 'y'; symlog when some values are 0. Returns the scale."""
    if not results.use_log(values):
        return "linear"
    positive = [v for v in values if v is not None and v > 0]
    setter = ax.set_xscale if axis == "x" else ax.set_yscale
    if len(positive) < len([v for v in values if v is not None]):
        setter("symlog", linthresh=min(positive), base=base)
        return "symlog"
    setter("log", base=base)
    # Plain numbers at 1, 2, 5 times each power (or each power of 2), not 10^k alone.
    axis_object = ax.xaxis if axis == "x" else ax.yaxis
    subs = (1.0,) if base == 2 else (1.0, 2.0, 5.0)
    axis_object.set_major_locator(ticker.LogLocator(base=base, subs=subs))
    axis_object.set_major_formatter(ticker.FuncFormatter(lambda v, _: f"{v:g}"))
    axis_object.set_minor_locator(ticker.NullLocator())   # 1-2-5 majors suffice (and minors are slow)
    return "log"


FIGSIZE = (11, 6)   # wide enough for the axes and the legend beside them
RIGHT_EDGE = 0.995  # the legend's right edge, in figure fractions
GAP = 0.012         # between the axes and the legend


def layout(fig):
    """Fixed margins: tight_layout() measured every tick label and took half the run."""
    fig.subplots_adjust(left=0.07, right=0.985, bottom=0.085, top=0.91)


def legend_outside(fig, ax, fontsize=7):
    """The legend in the right margin beside the axes, its top level with theirs, never over a
    point: the axes are narrowed to end left of it. More columns when one would be taller than the
    axes. Returns the legend (None when nothing is labelled)."""
    layout(fig)
    handles, labels = ax.get_legend_handles_labels()
    if not handles:
        return None
    renderer = fig.canvas.get_renderer()
    top = ax.get_position().y1
    axes_height = ax.get_window_extent(renderer).height
    for ncol in (1, 2, 3):
        legend = fig.legend(handles, labels, fontsize=fontsize, ncol=ncol, loc="upper right",
                            bbox_to_anchor=(RIGHT_EDGE, top), borderaxespad=0.0)
        box = legend.get_window_extent(renderer)
        if box.height <= axes_height or ncol == 3:
            break
        legend.remove()
    fig.subplots_adjust(right=RIGHT_EDGE - box.width / fig.bbox.width - GAP)
    return legend


def _overlap(a, b):
    """Area shared by boxes a and b, each (x0, y0, x1, y1)."""
    w = min(a[2], b[2]) - max(a[0], b[0])
    h = min(a[3], b[3]) - max(a[1], b[1])
    return w * h if w > 0 and h > 0 else 0.0


def marker_boxes(ax):
    """(label, box) of every marker drawn inside the axes, in display pixels: scatter points
    (s is the marker's area in points^2: a square of side sqrt(s)) and the markers of lines."""
    fig = ax.figure
    ax.get_xlim(), ax.get_ylim()   # applies a pending autoscale, or transData is stale
    scale = fig.dpi / 72.0
    frame = ax.get_window_extent(fig.canvas.get_renderer()).extents
    boxes = []

    def add(label, points, side_pt):
        half = side_pt * scale / 2.0
        for x, y in ax.transData.transform(points):
            if math.isfinite(x) and math.isfinite(y) and frame[0] <= x <= frame[2] and frame[1] <= y <= frame[3]:
                boxes.append((label, (x - half, y - half, x + half, y + half)))

    for c in ax.collections:
        offsets, sizes = c.get_offsets(), c.get_sizes()
        if len(offsets) and len(sizes) and c.get_visible():
            for i, point in enumerate(offsets):
                add(c.get_label(), [point], math.sqrt(sizes[i % len(sizes)]))
    for line in ax.get_lines():
        if line.get_marker() not in (None, "", " ", "None", "none") and line.get_visible():
            add(line.get_label(), line.get_xydata(), line.get_markersize())
    return boxes


# Where place_labels() tries a label: rings around its point (pixels at 100 dpi, scaled with the
# figure's), 16 directions each, upper right first.
RADII = (5, 9, 14, 20, 28, 38, 50, 64, 80, 100, 125, 155, 190, 230)
DIRECTIONS = [math.radians(45 + 22.5 * k * (-1) ** k) for k in range(16)]
PAD = 2.0   # pixels kept clear around markers and labels


def place_labels(ax, items, fontsize=6):
    """Annotates each (text, (x, y)) of items at the nearest position around its point whose box
    overlaps no marker, no label placed before it and lies inside the axes; the least overlapping
    position inside the axes when there is none. Labels more than a few pixels from their point get
    a leader line. Call after the axes' limits, scales and margins are final (legend_outside)."""
    fig = ax.figure
    renderer = fig.canvas.get_renderer()
    scale = fig.dpi / 100.0
    frame = ax.get_window_extent(renderer).extents
    obstacles = [box for _, box in marker_boxes(ax)]
    placed = []
    for text, anchor in items:
        probe = ax.text(0, 0, text, fontsize=fontsize, ha="left", va="bottom")
        extent = probe.get_window_extent(renderer)
        probe.remove()
        w, h = extent.width, extent.height
        ax_x, ax_y = ax.transData.transform(anchor)
        best, best_cost = None, None
        for radius in RADII:
            r = radius * scale
            for angle in DIRECTIONS:
                dx, dy = math.cos(angle), math.sin(angle)
                x0 = ax_x + r * dx - (0.0 if dx > 0.3 else w if dx < -0.3 else w / 2)
                y0 = ax_y + r * dy - (0.0 if dy > 0.3 else h if dy < -0.3 else h / 2)
                box = (x0, y0, x0 + w, y0 + h)
                if box[0] < frame[0] + PAD or box[2] > frame[2] - PAD or box[1] < frame[1] + PAD or box[3] > frame[3] - PAD:
                    continue
                padded = (x0 - PAD, y0 - PAD, x0 + w + PAD, y0 + h + PAD)
                cost = sum(_overlap(padded, o) for o in obstacles + placed)
                if best_cost is None or cost < best_cost:
                    best, best_cost = (box, r), cost
                if cost == 0.0:
                    break
            if best_cost == 0.0:
                break
        if best is None:   # larger than the axes: at the point, as before
            best = ((ax_x + 4, ax_y + 4, ax_x + 4 + w, ax_y + 4 + h), 0.0)
        box, r = best
        placed.append(box)
        points = 72.0 / fig.dpi
        leader = dict(arrowstyle="-", lw=0.5, color="#666666", shrinkA=0, shrinkB=2) if r > 10 * scale else None
        ax.annotate(text, anchor, xytext=((box[0] - ax_x) * points, (box[1] - ax_y) * points),
                    textcoords="offset points", fontsize=fontsize, ha="left", va="bottom", zorder=4,
                    arrowprops=leader, annotation_clip=False)


def chart_boxes(fig):
    """What box_problems() checks, in pixels of the saved PNG (the figure's dpi): the axes, the
    legend, each label (its text's box and its point) and each marker."""
    renderer = fig.canvas.get_renderer()
    ax = fig.axes[0]
    legends = [lg for lg in fig.legends] + ([ax.get_legend()] if ax.get_legend() else [])

    def extents(box):
        return [round(v, 2) for v in box.extents]

    def text_box(t):
        # The text's own box: an Annotation's get_window_extent() adds its leader line.
        if hasattr(t, "update_positions"):
            t.update_positions(renderer)
        return Text.get_window_extent(t, renderer)

    return {
        "figure": [fig.bbox.width, fig.bbox.height],
        "dpi": fig.dpi,
        "axes": extents(ax.get_window_extent(renderer)),
        "legend": extents(legends[0].get_window_extent(renderer)) if legends else None,
        "labels": [{"text": t.get_text(), "box": extents(text_box(t)),
                    "anchor": [round(v, 2) for v in ax.transData.transform(t.xy)]}
                   for t in ax.texts if hasattr(t, "xy")],
        "markers": [{"label": label, "box": [round(v, 2) for v in box]} for label, box in marker_boxes(ax)],
    }


def box_problems(boxes):
    """What is wrong with a chart's boxes (chart_boxes): a label over a marker (its own included) or
    over another label, a label outside the figure, the legend over the axes. [] when nothing."""
    problems = []
    labels, markers = boxes["labels"], boxes["markers"]
    for i, label in enumerate(labels):
        for marker in markers:
            if _overlap(label["box"], marker["box"]) > 0:
                problems.append(f"label '{label['text']}' covers a marker of {marker['label']}")
        for other in labels[i + 1:]:
            if _overlap(label["box"], other["box"]) > 0:
                problems.append(f"labels '{label['text']}' and '{other['text']}' overlap")
        x0, y0, x1, y1 = label["box"]
        if x0 < 0 or y0 < 0 or x1 > boxes["figure"][0] or y1 > boxes["figure"][1]:
            problems.append(f"label '{label['text']}' leaves the figure")
    if boxes["legend"] is not None and _overlap(boxes["legend"], boxes["axes"]) > 0:
        problems.append("the legend overlaps the axes")
    return problems


def title(ax, text, rows, extra=""):
    files = len({r.get("_source", "") for r in rows})
    notes = [n for n in (extra, results.gbuffer_note(rows), f"rows of {files} files" if files > 1 else "") if n]
    ax.set_title(text + ("\n" + "; ".join(notes) if notes else ""), fontsize=9)


def pareto_figure(rows, scene, size, kind):
    """The Pareto chart of one (scene, size): kind 'hard' (hard_mae) or 'soft' (soft_mae_penumbra,
    soft_mae when no row has it). Returns (figure, info) or None when nothing to draw; info holds
    y (the error column), front (rows), none (the row or None), scales."""
    if kind == "hard":
        y = "hard_mae"
        ylabel = "mean absolute visibility error vs hard reference"
    else:
        y = "soft_mae_penumbra" if any("soft_mae_penumbra" in r for r in rows) else "soft_mae"
        ylabel = ("mean absolute visibility error vs soft reference, in its penumbra"
                  if y == "soft_mae_penumbra" else "mean absolute visibility error vs soft reference")
    rows = [r for r in results.techniques(rows, NOT_CHARTED)
            if results.number(r.get(X)) is not None and results.number(r.get(y)) is not None]
    nones = [r for r in rows if r["technique"] == "none"]
    points = [r for r in rows if r["technique"] != "none"]
    if not points:
        return None
    fig, ax = plt.subplots(figsize=FIGSIZE)
    by_technique = results.group_by(points, lambda r: r["technique"])
    for technique, items in sorted(by_technique.items()):
        colour, marker = results.style(technique)
        ax.scatter([r[X] for r in items], [r[y] for r in items], label=technique, s=30, color=colour,
                   marker=marker, zorder=3)
    front = results.pareto_front(points, X, y)
    ax.plot([r[X] for r in front], [r[y] for r in front], "k--", lw=1, label="Pareto front", zorder=2)
    keys = {t: results.label_keys(items) for t, items in by_technique.items()}

    xs, ys = [r[X] for r in points], [r[y] for r in points]
    floors = [results.number(r.get("soft_reference_floor")) for r in points] if kind == "soft" else []
    floors = sorted(f for f in floors if f is not None)
    floor = floors[len(floors) // 2] if floors else None
    if floor is not None and floor > 0:
        ys_limits = ys + [floor]
    else:
        ys_limits = ys
    scales = (set_scale(ax, "x", xs + [r[X] for r in nones]), set_scale(ax, "y", ys_limits))

    def limits(values, scale):
        lo, hi = min(values), max(values)
        if scale == "log":
            return lo / 1.3, hi * 1.3
        pad = (hi - lo) * 0.08 or abs(hi) * 0.1 or 1.0
        return (max(lo - pad, 0.0) if lo >= 0 else lo - pad), hi + pad

    ylo, yhi = limits(ys_limits, scales[1])
    none = nones[0] if nones else None
    if none is not None:
        colour, _ = results.style("none")
        ax.axvline(none[X], color=colour, ls=":", lw=1, label=f"none: {none[X]:.3f} ms (no shadows)", zorder=1)
        off = "" if ylo <= none[y] <= yhi else ", off the chart"
        ax.axhline(none[y], color=colour, ls="-.", lw=1, label=f"none: error {none[y]:.4g}{off}", zorder=1)
    if floor is not None:
        rays = [results.number(r.get("soft_reference_rays")) for r in points]
        rays = sorted(r for r in rays if r is not None)
        text = "soft reference's own sampling error"
        if rays:
            text += f" ({int(rays[len(rays) // 2])} rays)"
        ax.axhspan(ylo, floor, color="#888888", alpha=0.15, lw=0, zorder=0)
        ax.axhline(floor, color="#888888", ls="--", lw=1, label=text, zorder=1)
    ax.set_ylim(ylo, yhi)
    xlo, xhi = limits(xs + [r[X] for r in nones], scales[0])
    ax.set_xlim(xlo, xhi)

    ax.set_xlabel("GPU milliseconds per frame (median)")
    ax.set_ylabel(ylabel)
    gpu = points[0].get("gpu", "")
    extra = "soft error inside the soft reference's penumbra" if y == "soft_mae_penumbra" else ""
    title(ax, f"Speed against accuracy: {scene} at {results.size_name(size)}" + (f" ({gpu})" if gpu else ""),
          points + nones, extra)
    ax.grid(alpha=0.3)
    legend_outside(fig, ax)
    # The front's labels last, once limits and margins are final: off every marker and each other.
    place_labels(ax, [(results.label(row, keys[row["technique"]]), (row[X], row[y])) for row in front])
    return fig, {"y": y, "front": front, "none": none, "scales": scales, "floor": floor}


def follows(rows, key, other):
    """True when `other` is a function of `key` over rows (swept together, like a radius with a grid)."""
    seen = {}
    for row in rows:
        if key in row:
            value = results.canonical(row.get(other))
            if seen.setdefault(results.canonical(row[key]), value) != value:
                return False
    return len(seen) > 1


def against_figure(rows, key, scene, xlabel, base=10, per_size=True):
    """GPU ms per frame against `key`, one line per (technique, other parameters[, size]).
    Returns (figure, info) or None; info holds series (label -> (technique, points)), scales."""
    by_technique = results.group_by(results.techniques(rows), lambda r: r["technique"])
    linked = {}
    for technique, items in by_technique.items():
        keys = {k for r in items for k in r if k != key and k.startswith(("param.", "scene."))}
        linked[technique] = {k for k in keys if follows(items, key, k)}
    series = {}
    for row in results.techniques(rows):
        x, t = results.number(row.get(key)), results.number(row.get(X))
        if x is None or t is None:
            continue
        others = tuple(sorted((k, results.canonical(v)) for k, v in row.items()
                              if k.startswith(("param.", "scene.")) and k != key
                              and k not in linked[row["technique"]]))
        size = results.size_of(row) if per_size else None
        series.setdefault((row["technique"], size, others, row.get("_source", "")), []).append((x, t))
    series = {k: sorted(v) for k, v in series.items() if len({p[0] for p in v}) > 1}
    if not series:
        return None
    sources = {k[3] for k in series}
    fig, ax = plt.subplots(figsize=FIGSIZE)
    drawn = {}
    count = {}
    for (technique, size, others, source), points in sorted(series.items(), key=lambda kv: str(kv[0])):
        colour, marker = results.style(technique)
        index = count.get(technique, 0)
        count[technique] = index + 1
        text = technique + (f" {results.size_name(size)}" if size else "")
        if len(sources) > 1:
            text += f" [{os.path.basename(source)}]"
        ls = "--" if technique in NOT_CHARTED else LINESTYLES[index % len(LINESTYLES)]
        ax.plot([p[0] for p in points], [p[1] for p in points], marker=marker, ms=4, color=colour, ls=ls,
                label=text)
        drawn[text] = (technique, points)
    xs = [p[0] for _, pts in drawn.values() for p in pts]
    ys = [p[1] for _, pts in drawn.values() for p in pts]
    scales = (set_scale(ax, "x", xs, base), set_scale(ax, "y", ys))
    ax.set_xlabel(xlabel)
    ax.set_ylabel("GPU milliseconds per frame (median)")
    title(ax, f"{scene}: frame time against {xlabel}", [r for r in rows if results.number(r.get(key)) is not None])
    ax.grid(alpha=0.3)
    legend_outside(fig, ax, fontsize=6)
    return fig, {"series": drawn, "scales": scales}


def triangles_figure(sweep):
    """GPU ms per frame against triangles for one scene sweep (results.scene_sweeps): one line per
    technique (and parameter set). Returns (figure, info) or None; info holds series, scenes."""
    rows = [r for r in results.techniques(sweep["rows"]) if results.number(r.get("triangles")) is not None
            and results.number(r.get(X)) is not None]
    by_technique = results.group_by(rows, lambda r: r["technique"])
    series = {}
    for technique, items in by_technique.items():
        keys = results.label_keys(items)
        for row in items:
            text = results.label(row, keys)
            series.setdefault(text, (technique, []))[1].append((results.number(row["triangles"]), row[X]))
    series = {k: (t, sorted(p)) for k, (t, p) in series.items() if len({x for x, _ in p}) > 1}
    if not series:
        return None
    fig, ax = plt.subplots(figsize=FIGSIZE)
    for text, (technique, points) in sorted(series.items()):
        colour, marker = results.style(technique)
        ax.plot([p[0] for p in points], [p[1] for p in points], marker=marker, ms=4, color=colour,
                ls="--" if technique in NOT_CHARTED else "-",
                label=text + (" (depth-only pass)" if technique == "depth-floor" else ""))
    xs = [p[0] for _, pts in series.values() for p in pts]
    ys = [p[1] for _, pts in series.values() for p in pts]
    scales = (set_scale(ax, "x", xs), set_scale(ax, "y", ys))
    ax.set_xlabel("triangles")
    ax.set_ylabel("GPU milliseconds per frame (median)")
    swept = ", ".join(sweep["keys"])
    title(ax, f"{sweep['scene']}: frame time against triangles ({swept} swept, {results.size_name(sweep['size'])})",
          rows)
    ax.grid(alpha=0.3)
    legend_outside(fig, ax, fontsize=7)
    return fig, {"series": series, "scenes": sorted({r["scene"] for r in rows}), "scales": scales}


def triangle_chart_names(sweeps):
    """(sweep, file name without .png): triangles-<scene>, then -<WxH> when the scene was swept at
    several sizes and -<file> when in several files (each file is a run of its own)."""
    named = []
    for sweep in sweeps:
        same = [s for s in sweeps if s["scene"] == sweep["scene"]]
        name = f"triangles-{sweep['scene']}"
        if len({s["size"] for s in same}) > 1:
            name += f"-{results.size_name(sweep['size'])}"
        if len({s["source"] for s in same}) > 1:
            name += "-" + os.path.splitext(os.path.basename(sweep["source"]))[0]
        named.append((sweep, name))
    return named


# Seed 001 sec. 5.3.1: its figures plot time against the number of translucent quads, one curve
# per technique (and per kernel: cssm2 9x9 and 3x3 are two, Fig. 5.3.D). assets/bench/seed001.json
# holds seed001-timing, assets/bench/seed001-composited.json the two composited specs: their rows
# usually come in two files (two runs), and a chart draws both, each curve from one file.
SEED001_QUADS_SPECS = ("seed001-timing", "seed001-composited-coarse")    # Figs. 5.3.A-E, 0-2000
SEED001_FINE_SPEC = "seed001-composited-fine"                            # Fig. 5.3.F, 0-30
COMPOSITED = "composited-translucent"
DRAWS = "translucent_draws_ms"
# 60 and 30 Hz frames: where seed 001 draws the line for composited shadows (real time only for
# single-digit counts); a reference line when the curves cross it.
FRAME_BUDGETS = ((60, 16.7), (30, 33.3))


def quad_series(rows, column=X):
    """label -> (technique, [(quads, value)]) sorted by quads, one series per (results.kernel_label,
    file): the label gains ' [file]' when one kernel label comes from several files (as on the
    sweep charts). Only series with values at two counts or more, in first-seen order."""
    series = {}
    for row in results.techniques(rows, NOT_CHARTED):
        x, y = results.number(row.get("scene.quads")), results.number(row.get(column))
        if x is not None and y is not None:
            key = (results.kernel_label(row), row.get("_source", ""))
            series.setdefault(key, (row["technique"], []))[1].append((x, y))
    series = {k: (t, sorted(p)) for k, (t, p) in series.items() if len({x for x, _ in p}) > 1}
    labels = [label for label, _ in series]
    # A file by its name, or by its path as given when two files share a name (two runs'
    # seed001.json), so no two curves share a label.
    sources = {source for _, source in series}
    names = {source: os.path.basename(source) for source in sources}
    if len(set(names.values())) < len(names):
        names = {source: source for source in sources}
    return {label + (f" [{names[source]}]" if labels.count(label) > 1 else ""): value
            for (label, source), value in series.items()}


def plot_quad_series(ax, series, suffix="", ls=None):
    """One line per label in the technique's colour and marker; a technique's second label (cssm2
    3x3 after 9x9) takes the next line style, as on the sweep charts."""
    count = {}
    for text, (technique, points) in series.items():
        colour, marker = results.style(technique)
        index = count.get(technique, 0)
        count[technique] = index + 1
        ax.plot([p[0] for p in points], [p[1] for p in points], marker=marker, ms=3, color=colour,
                ls=ls or LINESTYLES[index % len(LINESTYLES)], label=text + suffix)


def budget_lines(ax, ys):
    """The 60 and 30 Hz frame times as grey lines, each only when the curves reach it (a line far
    above every curve would squash them)."""
    for hz, budget in FRAME_BUDGETS:
        if ys and min(ys) <= budget <= max(ys):
            ax.axhline(budget, color="#888888", ls=":", lw=1, label=f"{budget:g} ms ({hz} Hz)", zorder=1)


def seed001_order(series):
    """Labels in the order of results.STYLE, a technique's labels in the rows' order (the spec
    sweeps cssm2's kernel 9 then 3: 9x9, the seed's own, gets the solid line)."""
    ids = list(results.STYLE)
    seen = list(series)
    return dict(sorted(series.items(), key=lambda kv: (ids.index(kv[1][0]) if kv[1][0] in ids else len(ids),
                                                        seen.index(kv[0]))))


def seed001_quads_figure(rows):
    """Seed 001 Figs. 5.3.A-E: GPU ms per frame against translucent quads (0-2000), one line per
    technique and kernel of seed001-timing, plus composited-translucent's seed001-composited-coarse
    rows. Returns (figure, info) or None; info holds series (label -> (technique, points)), scales."""
    rows = [r for r in rows if r.get("spec") in SEED001_QUADS_SPECS]
    series = seed001_order(quad_series(rows))
    if not series:
        return None
    fig, ax = plt.subplots(figsize=FIGSIZE)
    plot_quad_series(ax, series)
    ys = [y for _, pts in series.values() for _, y in pts]
    # Composited shadows grow as N^2 (seed 001 sec. 5.3.1), the others about linearly: a log y axis
    # when the curves span decades keeps the cheap techniques readable.
    scales = ("linear", set_scale(ax, "y", ys))
    budget_lines(ax, ys)
    ax.set_xlabel("translucent quads (scene.quads)")
    ax.set_ylabel("GPU milliseconds per frame (median)")
    # The coarse spec times few frames at few counts (O(N^2) draws a frame): said in the title.
    coarse = [r for r in rows if r.get("technique") == COMPOSITED]
    frames = sorted({results.canonical(r.get("frames")) for r in coarse if "frames" in r}, key=float)
    extra = (f"{COMPOSITED}: {len({results.canonical(r.get('scene.quads')) for r in coarse})} counts"
             + (f", {'/'.join(frames)} timed frames each" if frames else "")) if coarse else ""
    gpu = rows[0].get("gpu", "")
    title(ax, f"{rows[0].get('scene', '')}: frame time against translucent quads (seed 001 Figs. 5.3.A-E)"
          + (f" ({gpu})" if gpu else ""), rows, extra)
    ax.grid(alpha=0.3)
    legend_outside(fig, ax, fontsize=7)
    return fig, {"series": series, "scales": scales}


def seed001_fine_figure(rows):
    """Seed 001 Fig. 5.3.F: GPU ms per frame against translucent quads (0-30) of the
    seed001-composited-fine rows, one solid line per technique, and composited-translucent's
    per-quad loop ('translucent draws', inside its main pass) dashed in its colour. Returns
    (figure, info) or None; info holds series and draws (label -> (technique, points)), scales."""
    rows = [r for r in rows if r.get("spec") == SEED001_FINE_SPEC]
    series = seed001_order(quad_series(rows))
    if not series:
        return None
    draws = quad_series([r for r in rows if r.get("technique") == COMPOSITED], DRAWS)
    fig, ax = plt.subplots(figsize=FIGSIZE)
    plot_quad_series(ax, series, ls="-")
    plot_quad_series(ax, draws, suffix=": translucent draws (inside the main pass)", ls="--")
    ys = [y for _, pts in list(series.values()) + list(draws.values()) for _, y in pts]
    scales = ("linear", set_scale(ax, "y", ys))
    budget_lines(ax, ys)
    ax.set_xlabel("translucent quads (scene.quads)")
    ax.set_ylabel("GPU milliseconds (median)")
    gpu = rows[0].get("gpu", "")
    title(ax, f"{rows[0].get('scene', '')}: composited translucent shadows, 0-30 quads (seed 001 Fig. 5.3.F)"
          + (f" ({gpu})" if gpu else ""), rows)
    ax.grid(alpha=0.3)
    legend_outside(fig, ax, fontsize=7)
    return fig, {"series": series, "draws": draws, "scales": scales}


def save(made, path, dpi):
    """The PNG, and beside it <name>.boxes.json (chart_boxes) measured at the PNG's dpi."""
    if made is None:
        return None
    fig = made[0]
    fig.set_dpi(dpi)
    with open(os.path.splitext(path)[0] + ".boxes.json", "w") as f:
        json.dump(chart_boxes(fig), f, indent=1)
    fig.savefig(path, dpi=dpi)
    plt.close(fig)
    return path


def write_charts(rows, out_dir, dpi=120):
    """Every chart of the rows into out_dir; returns the paths written."""
    os.makedirs(out_dir, exist_ok=True)
    # Figures made at the PNG's dpi: labels are placed in the pixels they are saved in.
    with matplotlib.rc_context({"figure.dpi": dpi}):
        return [p for p in chart_files(rows, out_dir, dpi) if p]


def chart_files(rows, out_dir, dpi):
    """write_charts()'s charts, each path or None (nothing to draw)."""
    written = []
    rows = results.techniques(rows)
    charted = results.techniques(rows, NOT_CHARTED)
    for (scene, size), sized in results.by_scene_size(charted).items():
        for kind in ("hard", "soft"):
            path = os.path.join(out_dir, f"pareto-{scene}-{results.size_name(size)}-{kind}.png")
            written.append(save(pareto_figure(sized, scene, size, kind), path, dpi))
    for scene in sorted({r["scene"] for r in charted if r.get("scene")}):
        scene_rows = [r for r in charted if r.get("scene") == scene]
        keys = results.varying(scene_rows, "param.")
        if len({results.canonical(r.get("light_size")) for r in scene_rows if "light_size" in r}) > 1:
            keys.append("light_size")
        for key in keys:
            name = "sweep-" + key.replace("param.", "").replace("_", "-")
            base = 2 if key == "param.resolution" else 10
            written.append(save(against_figure(scene_rows, key, scene, key.replace("param.", ""), base=base),
                                os.path.join(out_dir, f"{name}-{scene}.png"), dpi))
        written.append(save(against_figure(scene_rows, "pixels", scene, "output pixels", per_size=False),
                            os.path.join(out_dir, f"resolution-{scene}.png"), dpi))
    for sweep, name in triangle_chart_names(results.scene_sweeps(rows)):
        written.append(save(triangles_figure(sweep), os.path.join(out_dir, name + ".png"), dpi))
    written.append(save(seed001_quads_figure(rows), os.path.join(out_dir, "seed001-quads.png"), dpi))
    written.append(save(seed001_fine_figure(rows), os.path.join(out_dir, "seed001-composited-fine.png"), dpi))
    return written


def parse_args(argv):
    parser = argparse.ArgumentParser(
        prog="charts.py", description="Charts (PNG) of shadowlab bench results: Pareto fronts, sweeps, triangles.",
        epilog="The older form `charts.py results.json OUT_DIR` still works (shadowlab report calls it so).")
    parser.add_argument("inputs", nargs="+", metavar="RESULTS", help="results files (.json or .csv) of shadowlab bench")
    parser.add_argument("--out", metavar="DIR", help="directory for the PNG files (default: charts)")
    parser.add_argument("--dpi", type=int, default=120, help="resolution of the PNG files (default: 120)")
    args = parser.parse_args(argv)
    if args.out is None:
        last = args.inputs[-1]
        if len(args.inputs) > 1 and not last.endswith((".json", ".csv")) and not os.path.isfile(last):
            args.out = args.inputs.pop()
        else:
            args.out = "charts"
    return args


def main(argv=None):
    args = parse_args(sys.argv[1:] if argv is None else argv)
    try:
        rows = results.load(args.inputs)
    except (OSError, ValueError) as e:
        print(f"charts.py: {e}", file=sys.stderr)
        return 1
    for path in write_charts(rows, args.out, args.dpi):
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
