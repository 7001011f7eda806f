#!/usr/bin/python3
"""The one loader and the shared helpers of the result tools (charts.py, ratios.py, table41.py).

    import results
    rows = results.load(["default.json", "seed000.json"])    # JSON or CSV, several files

`shadowlab bench` writes a JSON list of flat objects or a CSV file with one column per key.
load() reads either, turns CSV cells back into numbers, and normalises every row so the tools
read one set of names whatever the bench version that wrote the file:

  new name              old name (files written before it)
  frame_ms              gpu_frame_ms           GPU ms of a timed frame
  technique_passes_ms   gpu_technique_ms       the technique's own passes, summed
  main_ms               gpu_main_ms            the main (camera) pass
  floor_depth_ms        gpu_depth_floor_ms     depth-only pass of the same casters (old files: on
                                               the `depth-floor` rows only; copied here onto the
                                               rows of the same run, scene, size and resolution)
  floor_main_ms         -                      main pass of `none` (derived from the `none` row)
  shadow_term_ms        -                      main pass with the technique minus the main pass of
                                               `none`, same run, scene, size and view (derived)
  (the _p5 and _p95 columns of the timings follow the same renaming)

A value the bench did not write but the loader computed from other rows is listed in the row's
`_derived` set (results.derived(row, key)). Rows without `frame_ms` come from a bench that wrote
the accuracy G-buffer on every timed frame: they get `gbuffer_every_frame = True`, and a
shadow_term_ms derived from them is a difference of two main passes that both wrote it.

Loader bookkeeping lives in keys that start with `_`: `_source` (the file a row came from: rows of
one file are one run, and only rows of one run are ever compared) and `_derived`.

Also here: grouping by (scene, size), the parameter string of a row, the Pareto front, the log
scale rule, the scene sweeps behind the triangles chart, the curve label of seed 001's figures
(kernel_label), and STYLE, the fixed colour and marker of every technique. Standard library only.
"""
import csv
import json
import math
import os
import zlib
from collections import OrderedDict, defaultdict

# New column name -> the name older bench versions wrote.
RENAMED = OrderedDict([
    ("frame_ms", "gpu_frame_ms"),
    ("technique_passes_ms", "gpu_technique_ms"),
    ("main_ms", "gpu_main_ms"),
    ("floor_depth_ms", "gpu_depth_floor_ms"),
])
TIMING_SUFFIXES = ("", "_p5", "_p95")
BOOLEAN_COLUMNS = ("gbuffer_every_frame",)
# Keys that must agree for two rows to share a view (same scene, size and camera).
VIEW_PREFIXES = ("scene.", "view.")
VIEW_KEYS = ("scene", "width", "height", "view")

# Fixed colour and marker per technique id: the same on every chart. The ids of plugins/, the
# host's pseudo-techniques (reference, depth-floor) and the ids planned next.
STYLE = OrderedDict([
    ("none", ("#000000", "x")),
    ("planar", ("#8c564b", "p")),
    ("shadowmap", ("#1f77b4", "o")),
    ("pcf", ("#ff7f0e", "s")),
    ("adaptive-pcf", ("#d62728", "D")),
    ("vsm", ("#2ca02c", "^")),
    ("esm", ("#9467bd", "v")),
    ("evsm", ("#e377c2", "<")),
    ("msm", ("#17becf", ">")),
    ("pcss", ("#bcbd22", "P")),
    ("area-reference", ("#7f7f7f", "*")),
    ("reference", ("#393b79", "X")),
    ("depth-floor", ("#555555", "_")),
    ("csm", ("#aec7e8", "h")),
    ("psm", ("#ffbb78", "H")),
    ("lispsm", ("#98df8a", "8")),
    ("tsm", ("#ff9896", "d")),
    ("stochastic-sm", ("#c5b0d5", "o")),
    ("cssm2", ("#c49c94", "s")),
    ("translucent-shadows", ("#f7b6d2", "^")),
    ("composited-translucent", ("#9edae5", "p")),
    ("raytraced", ("#e6550d", "*")),
    ("shadow-volumes", ("#31a354", "X")),
    ("rbsm", ("#756bb1", "D")),
    ("edtsm", ("#636363", "v")),
    ("virtual-sm", ("#bd9e39", "P")),
])
FALLBACK_COLOURS = ("#4e79a7", "#f28e2b", "#e15759", "#76b7b2", "#59a14f",
                    "#edc948", "#b07aa1", "#ff9da7", "#9c755f", "#bab0ac")
FALLBACK_MARKERS = ("o", "s", "D", "^", "v", "<", ">", "P", "X", "*", "h", "p")


def style(technique):
    """(colour, marker) of a technique id: STYLE's entry, else one picked by a CRC of the id
    (the same on every run and every machine, unlike hash())."""
    if technique in STYLE:
        return STYLE[technique]
    code = zlib.crc32(str(technique).encode("utf-8"))
    return (FALLBACK_COLOURS[code % len(FALLBACK_COLOURS)],
            FALLBACK_MARKERS[(code // len(FALLBACK_COLOURS)) % len(FALLBACK_MARKERS)])


# ---------------------------------------------------------------------------------------------
# Loading and normalisation

def _cell(text):
    """A CSV cell back to what the JSON file would hold: numbers as int or float, text as is."""
    try:
        return int(text)
    except ValueError:
        pass
    try:
        value = float(text)
    except ValueError:
        return text
    return value


def _boolean(value):
    if isinstance(value, bool):
        return value
    if isinstance(value, (int, float)):
        return value != 0
    return str(value).strip().lower() in ("true", "1", "yes")


def read_file(path):
    """The raw rows of one results file (JSON list of objects, or CSV)."""
    if path.endswith(".csv"):
        with open(path, newline="") as f:
            rows = []
            for raw in csv.DictReader(f):
                rows.append({k: _cell(v) for k, v in raw.items() if k is not None and v not in ("", None)})
            return rows
    with open(path) as f:
        try:
            data = json.load(f)
        except json.JSONDecodeError as e:
            raise ValueError(f"{path}: not JSON ({e})") from None
    if isinstance(data, dict):        # a single row
        data = [data]
    if not isinstance(data, list) or not all(isinstance(r, dict) for r in data):
        raise ValueError(f"{path}: expected a JSON list of objects (the output of shadowlab bench)")
    return [dict(r) for r in data]


def load(paths, derive=True):
    """Every row of every file, normalised (see the module's docstring). `paths`: one path or a
    list. Rows keep their file order; each knows its file in `_source`."""
    if isinstance(paths, str):
        paths = [paths]
    rows = []
    for path in paths:
        rows += normalise(read_file(path), source=path, derive=derive)
    return rows


def normalise(rows, source="", derive=True):
    """Renames, flags and (with derive) the derived columns, in place; returns rows."""
    for row in rows:
        row["_source"] = source
        row["_derived"] = set(row.get("_derived", ()))
        new_style = "frame_ms" in row
        for new, old in RENAMED.items():
            for suffix in TIMING_SUFFIXES:
                if new + suffix not in row and old + suffix in row:
                    row[new + suffix] = row[old + suffix]
        for key in BOOLEAN_COLUMNS:
            if key in row:
                row[key] = _boolean(row[key])
        if "gbuffer_every_frame" not in row:
            row["gbuffer_every_frame"] = not new_style
    if derive:
        derive_columns(rows)
    return rows


def view_key(row):
    """What two rows must share to be one view: run, scene, size, scene parameters, camera."""
    parts = [("_source", row.get("_source"))]
    parts += [(k, canonical(row.get(k))) for k in VIEW_KEYS if k in row]
    parts += sorted((k, canonical(v)) for k, v in row.items() if k.startswith(VIEW_PREFIXES))
    return tuple(parts)


def derive_columns(rows):
    """floor_main_ms, shadow_term_ms and floor_depth_ms where the bench did not write them,
    from the `none` and `depth-floor` rows of the same run and view."""
    none_main = {}
    none_main_by_light = {}
    depth_floor = {}
    for row in rows:
        technique = row.get("technique")
        if technique == "none" and number(row.get("main_ms")) is not None:
            none_main.setdefault(view_key(row), row)
            none_main_by_light.setdefault((view_key(row), canonical(row.get("light_size"))), row)
        if technique == "depth-floor" and number(row.get("floor_depth_ms")) is not None:
            depth_floor.setdefault((view_key(row), canonical(row.get("param.resolution"))), row)
    for row in rows:
        technique = row.get("technique")
        if technique == "depth-floor":
            continue
        view = view_key(row)
        none = none_main_by_light.get((view, canonical(row.get("light_size")))) or none_main.get(view)
        if none is not None and "floor_main_ms" not in row:
            row["floor_main_ms"] = none["main_ms"]
            row["_derived"].add("floor_main_ms")
            if none.get("gbuffer_every_frame"):
                row["_derived"].add("gbuffer:floor_main_ms")
        if "shadow_term_ms" not in row and number(row.get("main_ms")) is not None and \
                number(row.get("floor_main_ms")) is not None:
            row["shadow_term_ms"] = 0.0 if technique == "none" else row["main_ms"] - row["floor_main_ms"]
            row["_derived"].add("shadow_term_ms")
            if row.get("gbuffer_every_frame") or "gbuffer:floor_main_ms" in row["_derived"]:
                row["_derived"].add("gbuffer:shadow_term_ms")
        if "floor_depth_ms" not in row and "param.resolution" in row:
            floor = depth_floor.get((view, canonical(row["param.resolution"])))
            if floor is not None:
                row["floor_depth_ms"] = floor["floor_depth_ms"]
                row["_derived"].add("floor_depth_ms")
    return rows


def derived(row, key):
    """True when the loader computed `key` from other rows (the bench did not write it)."""
    return key in row.get("_derived", ())


def derived_from_gbuffer(row, key):
    """True when `key` was derived from rows measured with the G-buffer on every frame."""
    return "gbuffer:" + key in row.get("_derived", ())


def gbuffer_note(rows):
    """A caption for rows measured with the accuracy G-buffer written on every frame ('' if none)."""
    rows = [r for r in rows if r.get("technique")]
    flagged = sum(1 for r in rows if r.get("gbuffer_every_frame"))
    if not flagged:
        return ""
    if flagged == len(rows):
        return "measured with the G-buffer on every frame"
    return f"{flagged} of {len(rows)} rows measured with the G-buffer on every frame"


# ---------------------------------------------------------------------------------------------
# Values and grouping

def number(value):
    """A finite float, or None."""
    if isinstance(value, bool):
        return None
    try:
        value = float(value)
    except (TypeError, ValueError):
        return None
    return value if math.isfinite(value) else None


def canonical(value):
    """One spelling per value, for matching: 2048, 2048.0 and '2048' are all '2048'."""
    if value is None:
        return ""
    if isinstance(value, bool):
        return "true" if value else "false"
    x = number(value)
    if x is None:
        return str(value)
    return str(int(x)) if x == int(x) and abs(x) < 1e15 else repr(x)


def matches(row, **match):
    """True when every key=value (canonical) holds; keys may be given as dict(**{'param.x': 1})."""
    return all(canonical(row.get(k)) == canonical(v) for k, v in match.items())


def where(rows, **match):
    return [r for r in rows if matches(r, **match)]


def first(rows, **match):
    found = where(rows, **match)
    return found[0] if found else None


def size_of(row):
    w, h = number(row.get("width")), number(row.get("height"))
    return (int(w), int(h)) if w is not None and h is not None else None


def size_name(size):
    return f"{size[0]}x{size[1]}"


def techniques(rows, exclude=()):
    """Rows that belong to a technique (not empty rows), less the excluded ids."""
    return [r for r in rows if r.get("technique") and r["technique"] not in exclude]


def group_by(rows, key):
    """OrderedDict key(row) -> rows, in first-seen order; rows whose key is None are left out."""
    groups = OrderedDict()
    for row in rows:
        k = key(row)
        if k is not None:
            groups.setdefault(k, []).append(row)
    return groups


def by_scene_size(rows):
    """(scene, (width, height)) -> rows, sorted by scene then size."""
    groups = group_by(rows, lambda r: (r["scene"], size_of(r)) if r.get("scene") and size_of(r) else None)
    return OrderedDict(sorted(groups.items()))


def by_source(rows):
    """_source -> rows, in file order: one run per file."""
    return group_by(rows, lambda r: r.get("_source", ""))


def varying(rows, prefix="param."):
    """Keys with the prefix that take more than one value over the rows that have them."""
    values = defaultdict(set)
    for row in rows:
        for key, value in row.items():
            if key.startswith(prefix):
                values[key].add(canonical(value))
    return sorted(k for k, v in values.items() if len(v) > 1)


def label_keys(rows):
    """The keys that tell the rows of one technique apart on a chart: the varying `param.*` keys,
    and light_size when it varies too."""
    keys = varying(rows, "param.")
    if len({canonical(r.get("light_size")) for r in rows if "light_size" in r}) > 1:
        keys.append("light_size")
    return keys


def param_string(row, keys):
    """'kernel=5 resolution=2048': the row's values of keys (usually varying(rows of a chart))."""
    return " ".join(f"{k.split('.', 1)[1] if '.' in k else k}={canonical(row[k])}" for k in keys if k in row)


def label(row, keys):
    """The technique id followed by its parameter string."""
    return " ".join(p for p in (row.get("technique", ""), param_string(row, keys)) if p)


def kernel_label(row):
    """'cssm2 9x9': the technique id, with its kernel for the techniques seed 001 times at more than
    one kernel or at a kernel of its own (cssm2, stochastic-sm; Figs. 5.3.C-D), each a curve there."""
    if row.get("technique") in ("cssm2", "stochastic-sm") and row.get("param.kernel") not in (None, ""):
        kernel = canonical(row.get("param.kernel"))
        return f"{row['technique']} {kernel}x{kernel}"
    return row.get("technique", "")


def pareto_front(rows, x, y):
    """The rows no other row beats on both x and y (lower is better), sorted by x, strictly
    falling y. Rows without finite x or y are left out."""
    points = [(number(r.get(x)), number(r.get(y)), i) for i, r in enumerate(rows)]
    points = sorted(p for p in points if p[0] is not None and p[1] is not None)
    front, best = [], float("inf")
    for px, py, i in points:
        if py < best:
            front.append(rows[i])
            best = py
    return front


def use_log(values, ratio=10.0):
    """Log scale when the positive values span more than `ratio` (max/min > ratio)."""
    positive = [v for v in (number(v) for v in values) if v is not None and v > 0]
    return len(positive) > 1 and max(positive) / min(positive) > ratio


def scene_sweeps(rows):
    """The scene-parameter sweeps: for each (run, scene, size), the rows whose `scene.*`
    parameters take more than one value there. Returns a list of dicts with scene, size, keys
    (the varying scene.* keys), source and rows, in first-seen order. Rows of different scenes
    are never in one sweep."""
    sweeps = []
    groups = group_by(rows, lambda r: (r.get("_source", ""), r["scene"], size_of(r))
                      if r.get("scene") and size_of(r) else None)
    for (source, scene, size), items in groups.items():
        keys = varying(items, "scene.")
        if not keys:
            continue
        swept = [r for r in items if all(k in r for k in keys)]
        sweeps.append({"source": source, "scene": scene, "size": size, "keys": keys, "rows": swept})
    return sweeps


def run_line(row):
    """'GPU ..., driver ..., date, build ...' of a row's environment."""
    return (f"GPU {row.get('gpu', '?')}, driver {row.get('driver', '?')}, {row.get('date', '?')}, "
            f"build {row.get('commit', '?')}")


def write_text(text, out_dir, name):
    """Writes text to out_dir/name (creating out_dir); returns the path."""
    os.makedirs(out_dir, exist_ok=True)
    path = os.path.join(out_dir, name)
    with open(path, "w") as f:
        f.write(text)
    return path
