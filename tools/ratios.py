#!/usr/bin/python3
"""The ratios the project reports from GPU runs (issues 5, 6 and 10), as Markdown.

    python3 tools/ratios.py default.json seed000.json fast-passes.json [--out DIR]

Inputs: results of `shadowlab bench` (JSON or CSV), typically `--spec assets/bench/default.json`
and `--spec assets/bench/seed000.json`. Each file is one run: every ratio compares rows of one
file (one run on one machine), never rows of two files. Without --out the Markdown goes to
stdout; with it, to DIR/ratios.md (and that path is printed). When more than one file adds rows
to a table, the table gains a `file` column.

Sections (each appears when its rows exist): the shadow pass against the depth-only floor; the
frame-time overhead of shadowmap over none; host CPU time per frame; time against triangle count
(every sweep of one scene's `scene.*` parameter with none and shadowmap rows); adaptive PCF and
VSM against PCF; every technique at the Fig. 4.15 settings; PCSS against light size; issue 10's
fast passes (fast-passes.json: moment passes against the depth floor, PCF gather against taps,
the host depth pre-pass on forest, PCSS's sample grids); seed 001's translucent casters against the
quad count (seed001.json: Figs. 5.3.A-D) and composited translucent shadows (seed001-composited.json:
Figs. 5.3.E-F; the counts inside a 60 Hz and a 30 Hz frame and the exponent of its per-quad loop).

Columns beyond frame time: `technique passes ms` (technique_passes_ms, the technique's own passes
summed), `shadow term ms` (shadow_term_ms: the main pass with the technique minus the main pass
with `none`) and ratios against the floors (floor_depth_ms, a depth-only pass of the same casters
at the row's resolution; floor_main_ms, the main pass of `none`). Files from before those columns:
see tools/results.py; values it derived from rows measured with the G-buffer on every frame are
marked with a dagger.
"""
import argparse
import math
import os
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import results  # noqa: E402

NAN = float("nan")
DAGGER = "\u2020"
SHADOW_SCENES = ("cube", "forest")     # the scenes default.json sweeps over shadow-map resolution
OVERHEAD_SCENES = ("cube", "spheres", "contact", "overlap", "pillars", "forest")
SIZES = ((1280, 720), (1920, 1080), (2560, 1440))
SEED_SCENES = ("cube", "dragon-like")
FIG415_SCENES = ("cube", "dragon-like", "contact", "dense")


class Table:
    """A Markdown table whose rows come from one or more files: a `file` column when several."""

    def __init__(self, headers, aligns):
        self.headers, self.aligns, self.rows = list(headers), list(aligns), []
        self.daggers = False

    def add(self, source, cells):
        self.rows.append((source, [str(c) for c in cells]))
        self.daggers = self.daggers or any(c.endswith(DAGGER) for _, cs in self.rows[-1:] for c in cs)

    def drop_empty(self, index):
        """Removes column `index` when every row has n/a there (a ratio no file could give)."""
        if self.rows and all(cells[index] == "n/a" for _, cells in self.rows):
            del self.headers[index], self.aligns[index]
            for _, cells in self.rows:
                del cells[index]

    def lines(self):
        several = len({s for s, _ in self.rows}) > 1
        headers = (["file"] if several else []) + self.headers
        aligns = (["---"] if several else []) + self.aligns
        out = ["| " + " | ".join(headers) + " |", "|" + "|".join(aligns) + "|"]
        for source, cells in self.rows:
            out.append("| " + " | ".join(([os.path.basename(source)] if several else []) + cells) + " |")
        return out


def ms(row, key, digits=3):
    """A timing cell: the value, a dagger when derived from G-buffer rows, n/a when absent."""
    value = results.number((row or {}).get(key))
    if value is None:
        return "n/a"
    return f"{value:.{digits}f}" + (DAGGER if results.derived_from_gbuffer(row, key) else "")


def ratio(row, numerator, denominator, digits=2, suffix="x"):
    a, b = results.number((row or {}).get(numerator)), results.number((row or {}).get(denominator))
    if a is None or b is None or b <= 1e-9:
        return "n/a"
    gbuffer = results.derived_from_gbuffer(row, numerator) or results.derived_from_gbuffer(row, denominator)
    return f"{a / b:.{digits}f}{suffix}" + (DAGGER if gbuffer else "")


def quotient(a, b, pattern):
    """pattern.format(a / b), or n/a when b is 0 (a no-op driver's timings)."""
    return pattern.format(a / b) if b else "n/a"


def passes_and_term(row):
    return f"{ms(row, 'technique_passes_ms')} / {ms(row, 'shadow_term_ms')}"


DAGGER_NOTE = (f"{DAGGER} derived by tools/results.py from rows measured with the G-buffer on every frame: "
               "shadow term = main pass with the technique minus the main pass with `none` (same file, scene "
               "and size); none's main pass taken from the `none` row. A bench that writes `shadow_term_ms` "
               "measures it without the G-buffer.\n")


def section_depth_floor(runs):
    out = ["## Shadow pass against the depth-only floor (same geometry, resolution and light)\n"]
    t = Table(["scene", "resolution", "depth floor ms", "shadowmap shadow pass ms", "ratio"],
              ["---", "---:", "---:", "---:", "---:"])
    for source, rows in runs.items():
        for scene in SHADOW_SCENES:
            maps = [r for r in results.where(rows, scene=scene, technique="shadowmap", width=1920)
                    if "gpu_shadow_map_ms" in r]
            for res in sorted({results.number(r.get("param.resolution")) for r in maps} - {None}):
                sm = [r for r in maps if results.matches(r, **{"param.resolution": res})
                      and results.number(r.get("floor_depth_ms")) is not None]
                if sm:
                    a, b = sm[0]["floor_depth_ms"], sm[0]["gpu_shadow_map_ms"]
                    t.add(source, [scene, int(res), f"{a:.3f}", f"{b:.3f}", quotient(b, a, "{:.2f}x")])
    return out + t.lines(), [t]


def section_overhead(runs):
    out = ["\n## Frame-time overhead of shadowmap (2048) over none, 1920x1080\n"]
    t = Table(["scene", "none ms", "shadowmap ms", "overhead", "shadow term ms", "technique passes ms",
               "passes / depth floor", "main / none's main"],
              ["---", "---:", "---:", "---:", "---:", "---:", "---:", "---:"])
    for source, rows in runs.items():
        for scene in OVERHEAD_SCENES:
            none = results.where(rows, scene=scene, technique="none", width=1920)
            sm = results.where(rows, scene=scene, technique="shadowmap", width=1920, **{"param.resolution": 2048})
            if none and sm:
                a, b = none[0]["frame_ms"], sm[0]["frame_ms"]
                t.add(source, [scene, f"{a:.3f}", f"{b:.3f}", f"+{b - a:.3f} ms ({quotient(100 * (b - a), a, '{:.0f}%')})",
                               ms(sm[0], "shadow_term_ms"), ms(sm[0], "technique_passes_ms"),
                               ratio(sm[0], "technique_passes_ms", "floor_depth_ms"),
                               ratio(sm[0], "main_ms", "floor_main_ms", 3)])
    return out + t.lines(), [t]


def section_cpu(runs):
    out = ["\n## Host CPU time per frame (median of medians, submission included, waits for the GPU excluded)\n"]
    wait = any("cpu_wait_ms" in r for rows in runs.values() for r in rows)
    t = Table(["scene", "techniques", "median ms", "max ms"] + (["CPU wait ms (median)"] if wait else []),
              ["---", "---:", "---:", "---:"] + (["---:"] if wait else []))
    for source, rows in runs.items():
        rows = results.techniques(rows, ("depth-floor",))
        for scene in results.group_by(rows, lambda r: r.get("scene")):
            items = [r for r in rows if r.get("scene") == scene and results.number(r.get("cpu_frame_ms")) is not None]
            if not items:
                continue
            values = [r["cpu_frame_ms"] for r in items]
            cells = [scene, f"{len(values)} rows", f"{statistics.median(values):.3f}", f"{max(values):.3f}"]
            if wait:
                waits = [results.number(r.get("cpu_wait_ms")) for r in items]
                waits = [w for w in waits if w is not None]
                cells.append(f"{statistics.median(waits):.3f}" if waits else "n/a")
            t.add(source, cells)
    return out + t.lines(), [t]


def section_triangles(runs):
    out, tables = [], []
    for source, rows in runs.items():
        for sweep in results.scene_sweeps(rows):
            items = sweep["rows"]
            steps = results.group_by(items, lambda r: tuple(results.canonical(r.get(k)) for k in sweep["keys"]))
            t = Table(["triangles", "none frame ms", "shadowmap frame ms", "shadow pass ms", "depth floor ms",
                       "shadow term ms", "passes / depth floor"],
                      ["---:", "---:", "---:", "---:", "---:", "---:", "---:"])
            for key, step in sorted(steps.items(), key=lambda kv: [results.number(v) or 0 for v in kv[0]]):
                none = results.first(step, technique="none")
                sm = results.first(step, technique="shadowmap")
                floor = results.first(step, technique="depth-floor")
                if not (none and sm):
                    continue
                depth = results.number(sm.get("floor_depth_ms"))
                if depth is None and floor:
                    depth = results.number(floor.get("floor_depth_ms"))
                t.add(source, [f"{int(results.number(none['triangles'])):,}", f"{none['frame_ms']:.3f}",
                               f"{sm['frame_ms']:.3f}", ms(sm, "gpu_shadow_map_ms"),
                               f"{depth if depth is not None else NAN:.3f}", ms(sm, "shadow_term_ms"),
                               f"{sm['technique_passes_ms'] / depth:.2f}x" if depth else "n/a"])
            if len(t.rows) > 1:
                swept = ", ".join(sweep["keys"])
                out += [f"\n## Time against triangle count ({sweep['scene']}, {swept} swept, "
                        f"{results.size_name(sweep['size'])})\n"] + t.lines()
                tables.append(t)
    return out, tables


def section_kernels(runs):
    out = ["\n## Adaptive PCF against PCF (same kernel footprint, 1024 map), seed 000: +15-104% FPS (smallest "
           "kernel), +392-1473% (largest)\n"]
    a_table = Table(["scene", "size", "n", "PCF ms", "adaptive ms", "FPS gain", "PCF soft MAE", "adaptive soft MAE",
                     "early-out rate", "PCF passes / term ms", "adaptive passes / term ms"],
                    ["---", "---", "---:", "---:", "---:", "---:", "---:", "---:", "---:", "---:", "---:"])
    v_table = Table(["scene", "size", "n", "PCF ms", "VSM ms", "VSM/PCF", "PCF soft MAE", "VSM soft MAE",
                     "PCF passes / term ms", "VSM passes / term ms"],
                    ["---", "---", "---:", "---:", "---:", "---:", "---:", "---:", "---:", "---:"])
    for source, s in runs.items():
        for scene in SEED_SCENES:
            for w, h in SIZES:
                for n in (3, 7, 11, 15):
                    p = results.first(s, spec="pcf-kernel", scene=scene, width=w, **{"param.kernel": n})
                    a = results.first(s, spec="adaptive-kernel", scene=scene, width=w, **{"param.grid": n})
                    if p and a:
                        gain = quotient(100 * (p["frame_ms"] - a["frame_ms"]), a["frame_ms"], "{:+.0f}%")
                        a_table.add(source, [scene, f"{w}x{h}", n, f"{p['frame_ms']:.3f}", f"{a['frame_ms']:.3f}",
                                             gain, f"{p.get('soft_mae', NAN):.4f}", f"{a.get('soft_mae', NAN):.4f}",
                                             f"{a.get('stat.early_out_rate', NAN):.2f}", passes_and_term(p),
                                             passes_and_term(a)])
        for scene in SEED_SCENES:
            for w, h in SIZES:
                for n in (1, 3, 5, 7, 9, 11, 13, 15):
                    p = results.first(s, spec="pcf-kernel", scene=scene, width=w, **{"param.kernel": n})
                    v = results.first(s, spec="vsm-kernel", scene=scene, width=w, **{"param.kernel": 2 * n + 1})
                    if p and v:
                        v_table.add(source, [scene, f"{w}x{h}", n, f"{p['frame_ms']:.3f}", f"{v['frame_ms']:.3f}",
                                             quotient(v["frame_ms"], p["frame_ms"], "{:.2f}"), f"{p.get('soft_mae', NAN):.4f}",
                                             f"{v.get('soft_mae', NAN):.4f}", passes_and_term(p), passes_and_term(v)])
    out += a_table.lines()
    out += ["\n## VSM with twice the kernel (2n+1 blur) against PCF n x n, 1024 map\n"] + v_table.lines()
    return out, [a_table, v_table]


def section_fig415(runs):
    out = ["\n## Every technique at 1024 map, 1920x1080, 11x11 kernels (seed 000 Fig. 4.15)\n"]
    t = Table(["scene", "technique", "frame ms", "technique passes ms", "shadow term ms", "MiB", "hard MAE",
               "soft MAE", "passes / depth floor", "main / none's main"],
              ["---", "---", "---:", "---:", "---:", "---:", "---:", "---:", "---:", "---:"])
    bullets = []
    for source, s in runs.items():
        for scene in FIG415_SCENES:
            for r in results.where(s, spec="fig415", scene=scene):
                t.add(source, [scene, r["technique"], f"{r['frame_ms']:.3f}", f"{r['technique_passes_ms']:.3f}",
                               ms(r, "shadow_term_ms"), f"{(results.number(r.get('gpu_bytes')) or 0) / 1048576:.1f}",
                               f"{r.get('hard_mae', NAN):.4f}", f"{r.get('soft_mae', NAN):.4f}",
                               ratio(r, "technique_passes_ms", "floor_depth_ms"),
                               ratio(r, "main_ms", "floor_main_ms", 3)])
        for scene in FIG415_SCENES:
            p = results.first(s, spec="fig415", scene=scene, technique="pcss")
            a = results.first(s, spec="fig415", scene=scene, technique="adaptive-pcf")
            if p and a:
                line = (f"{scene}: frame {quotient(p['frame_ms'], a['frame_ms'], '{:.2f}x')}, technique passes "
                        f"{p['technique_passes_ms'] / max(a['technique_passes_ms'], 1e-9):.2f}x")
                pt, at = results.number(p.get("shadow_term_ms")), results.number(a.get("shadow_term_ms"))
                if pt is not None and at is not None and at > 1e-3:
                    gbuffer = results.derived_from_gbuffer(p, "shadow_term_ms") or \
                        results.derived_from_gbuffer(a, "shadow_term_ms")
                    line += f", shadow term {pt / at:.2f}x" + (DAGGER if gbuffer else "")
                bullets.append((source, line))
                t.daggers = t.daggers or line.endswith(DAGGER)
    t.drop_empty(8)
    out += t.lines()
    if bullets:
        several = len({source for source, _ in bullets}) > 1
        out += ["\nPCSS against adaptive PCF (seed 000: about 2x):\n"]
        out += [f"- {os.path.basename(source) + ': ' if several else ''}{line}" for source, line in bullets]
    return out, [t]


def section_light_size(runs):
    out = ["\n## PCSS against light size (1024 map)\n"]
    t = Table(["scene", "size", "light size (deg)", "frame ms", "soft MAE", "penumbra share", "technique passes ms",
               "shadow term ms"],
              ["---", "---", "---:", "---:", "---:", "---:", "---:", "---:"])
    for source, s in runs.items():
        for r in results.where(s, spec="pcss-light"):
            t.add(source, [r["scene"], f"{r['width']}x{r['height']}", f"{r['light_size']:.2f}", f"{r['frame_ms']:.3f}",
                           f"{r.get('soft_mae', NAN):.4f}", f"{r.get('technique_penumbra_fraction', 0):.4f}",
                           ms(r, "technique_passes_ms"), ms(r, "shadow_term_ms")])
    return out + t.lines(), [t]


def section_fast_passes(runs):
    """Issue 10's targets (assets/bench/fast-passes.json), each a ratio within one run: moment
    techniques' passes against the depth floor (target at most 3x), PCF's gather against its taps
    (shadow term at 11x11, target at most 0.4x), the host depth pre-pass on forest (every filtered
    technique's frame at most 2x shadowmap's) and what PCSS's sample counts cost there."""
    out, tables = [], []
    moments = Table(["technique", "scene", "resolution", "blur", "technique passes ms", "depth floor ms",
                     "passes / floor", "soft MAE"], ["---", "---", "---:", "---", "---:", "---:", "---:", "---:"])
    for source, s in runs.items():
        for r in results.techniques(results.where(s, spec="moment-blur"), exclude=("depth-floor",)):
            moments.add(source, [r["technique"], r["scene"], results.canonical(r.get("param.resolution")),
                                 r.get("param.blur", ""), ms(r, "technique_passes_ms"), ms(r, "floor_depth_ms"),
                                 ratio(r, "technique_passes_ms", "floor_depth_ms"), f"{r.get('soft_mae', NAN):.5f}"])
    if moments.rows:
        out += ["\n## Moment techniques: their passes against the depth-only floor (5-tap blur; target at most 3x)\n"]
        out += moments.lines()
    tables.append(moments)

    gather = Table(["scene", "kernel", "bilinear taps", "cone bias", "taps term ms", "gather term ms", "gather / taps",
                    "folded term ms", "folded / taps", "taps soft MAE", "gather soft MAE", "folded soft MAE"],
                   ["---", "---:", "---", "---", "---:", "---:", "---:", "---:", "---:", "---:", "---:", "---:"])
    for source, s in runs.items():
        rows = results.where(s, spec="pcf-gather") + results.where(s, spec="pcf-gather-bilinear")
        for r in rows:
            if results.canonical(r.get("param.sampling")) != "taps":
                continue
            keys = {k: r.get(k) for k in ("scene", "param.kernel", "param.cone_bias", "param.hardware_filter")}
            cells = []
            maes = []
            for sampling in ("gather", "folded"):
                g = results.first([x for x in rows if results.canonical(x.get("param.sampling")) == sampling], **keys)
                term_ratio = NAN
                if g is not None and results.number(r.get("shadow_term_ms")) and results.number(g.get("shadow_term_ms")) is not None:
                    term_ratio = g["shadow_term_ms"] / r["shadow_term_ms"]
                cells += [ms(g, "shadow_term_ms") if g else "", f"{term_ratio:.2f}x" if g else ""]
                maes.append(f"{g.get('soft_mae', NAN):.5f}" if g else "")
            gather.add(source, [r["scene"], results.canonical(r.get("param.kernel")),
                                results.canonical(r.get("param.hardware_filter")), results.canonical(r.get("param.cone_bias")),
                                ms(r, "shadow_term_ms")] + cells + [f"{r.get('soft_mae', NAN):.5f}"] + maes)
    if gather.rows:
        out += ["\n## PCF: gather and folded against the tap loop, shadow term (2048 map, 1920x1080; target at most 0.4x at 11x11)\n"]
        out += gather.lines()
    tables.append(gather)

    # A technique's variant in the pre-pass rows: the parameters those specs sweep besides the pre-pass.
    variant_keys = ("param.classify", "param.search_bound", "param.sampling")

    def variant(r):
        values = [f"{k[len('param.'):]} = {r[k]}" for k in variant_keys if r.get(k) not in (None, "")]
        return r["technique"] + (f" ({', '.join(values)})" if values else "")

    prepass = Table(["technique", "frame ms without", "frame ms with", "with / shadowmap with", "shadow term ms with",
                     "pre-pass ms"], ["---", "---:", "---:", "---:", "---:", "---:"])
    samples = Table(["search grid", "filter grid", "search bound", "frame ms", "shadow term ms", "frame / shadowmap with pre-pass"],
                    ["---:", "---:", "---", "---:", "---:", "---:"])
    for source, s in runs.items():
        rows = results.where(s, spec="depth-prepass")
        base = results.first(rows, technique="shadowmap", depth_prepass=1)
        for name in dict.fromkeys(variant(r) for r in rows):
            without = results.first([r for r in rows if variant(r) == name], depth_prepass=0)
            with_ = results.first([r for r in rows if variant(r) == name], depth_prepass=1)
            if without is None or with_ is None:
                continue
            relative = f"{with_['frame_ms'] / base['frame_ms']:.2f}x" if base else "n/a"
            prepass.add(source, [name, ms(without, "frame_ms"), ms(with_, "frame_ms"), relative,
                                 ms(with_, "shadow_term_ms"), ms(with_, "depth_prepass_ms")])
        for r in results.where(s, spec="pcss-samples"):
            relative = f"{r['frame_ms'] / base['frame_ms']:.2f}x" if base else "n/a"
            samples.add(source, [results.canonical(r.get("param.search_grid")), results.canonical(r.get("param.filter_grid")),
                                 str(r.get("param.search_bound", "")), ms(r, "frame_ms"), ms(r, "shadow_term_ms"), relative])
    if prepass.rows:
        out += ["\n## Host depth pre-pass on forest (5000 trees, 1920x1080; target: every filtered technique at most 2x shadowmap with it)\n"]
        out += prepass.lines()
    if samples.rows:
        out += ["\nPCSS's sample grids on forest with the pre-pass (its defaults: search 6, filter 8, search bound depth-range):\n"]
        out += samples.lines()
    tables += [prepass, samples]
    return out, tables


def section_seed001(runs):
    """Seed 001 Figs. 5.3.A-D (assets/bench/seed001.json): GPU time of the translucent techniques
    against the number of translucent quads on glass-field, and the seed's three claims as ratios
    within the run: translucent shadows cost about Williams + 1 ms at every count; CSSM2 9x9 is
    above 7 ms near 2000 quads and 3x3 just above 5 ms (RTX 3070)."""
    out = ["\n## Seed 001: translucent casters on glass-field (1920x1080, 2048 map), against the quad count\n"]
    t = Table(["technique", "quads", "frame ms", "technique passes ms", "main ms", "shadow term ms"],
              ["---", "---:", "---:", "---:", "---:", "---:"])
    deltas, tables = [], [t]
    for source, s in runs.items():
        rows = results.where(s, spec="seed001-timing")
        name = results.kernel_label
        counts = sorted({int(results.number(r.get("scene.quads")) or 0) for r in rows})
        shown = [c for c in counts if c % 500 == 0]
        for technique in dict.fromkeys(name(r) for r in rows):
            for count in shown:
                r = next((x for x in rows if name(x) == technique and results.number(x.get("scene.quads")) == count), None)
                if r:
                    t.add(source, [technique, count, ms(r, "frame_ms"), ms(r, "technique_passes_ms"), ms(r, "main_ms"),
                                   ms(r, "shadow_term_ms")])
        williams = {results.number(r.get("scene.quads")): r for r in rows if r["technique"] == "shadowmap"}
        extra = [r["frame_ms"] - williams[results.number(r.get("scene.quads"))]["frame_ms"]
                 for r in rows if r["technique"] == "translucent-shadows" and results.number(r.get("scene.quads")) in williams]
        if extra:
            deltas.append(f"translucent-shadows costs shadowmap + {min(extra):.2f} to {max(extra):.2f} ms over the "
                          f"{len(extra)} counts (seed 001: about + 1 ms at every count)")
        last = max(counts) if counts else None
        for technique in ("cssm2 9x9", "cssm2 3x3"):
            r = next((x for x in rows if name(x) == technique and results.number(x.get("scene.quads")) == last), None)
            if r:
                deltas.append(f"{technique} at {last} quads: {r['frame_ms']:.3f} ms a frame, "
                              f"{r['frame_ms'] / williams[last]['frame_ms']:.2f}x shadowmap's "
                              f"(seed 001: above 7 ms for 9x9, just above 5 ms for 3x3, on an RTX 3070)")
    if deltas:
        out += t.lines() + [""] + [f"- {line}" for line in deltas]
    return out, tables


# Seed 001 Figs. 5.3.E-F (assets/bench/seed001-composited.json).
COMPOSITED = "composited-translucent"
COMPOSITED_FINE_COUNTS = (0, 1, 2, 5, 10, 20, 30)
# The 60 and 30 Hz frames, to one decimal as the section prints them (16.7 ms, not 1000/60 = 16.67:
# a frame of 16.68 ms counts as 60 Hz here).
FRAME_BUDGETS = ((60, 16.7), (30, 33.3))
# The fit leaves out the small counts, where the quad-independent part of the loop's time (its
# scope, state changes) is not yet small against the N^2 draws.
EXPONENT_MIN_QUADS = 100


def quads(row):
    """The row's scene.quads as an int, or None."""
    value = results.number((row or {}).get("scene.quads"))
    return int(value) if value is not None else None


def loglog_exponent(points, min_x=EXPONENT_MIN_QUADS):
    """(k, n): the slope k of log y against log x by least squares over the n points (x, y) with
    x >= min_x and y > 0, the exponent of y ~ x^k; (None, n) with fewer than two distinct x."""
    pts = [(math.log(x), math.log(y)) for x, y in points
           if x is not None and y is not None and x >= min_x and x > 0 and y > 0]
    if len({x for x, _ in pts}) < 2:
        return None, len(pts)
    mx = sum(x for x, _ in pts) / len(pts)
    my = sum(y for _, y in pts) / len(pts)
    sxx = sum((x - mx) ** 2 for x, _ in pts)
    sxy = sum((x - mx) * (y - my) for x, y in pts)
    return sxy / sxx, len(pts)


def within_budget(points, budget):
    """(largest, above, first_over) over the points (count, frame ms): the largest count whose frame
    is at most `budget` ms, the next measured count above it (every count above the largest is
    over budget), and the smallest count over budget (below `largest` when the curve is noisy).
    Each None when there is none."""
    points = sorted(points)
    ok = [c for c, t in points if t <= budget]
    over = [c for c, t in points if t > budget]
    largest = max(ok) if ok else None
    above = next((c for c, _ in points if largest is None or c > largest), None)
    return largest, above, (min(over) if over else None)


def budget_text(points, hz, budget):
    """'at most 16.7 ms (60 Hz) up to 7 quads (8: 17.214 ms)' for the points (count, frame ms)."""
    frames = dict(points)
    largest, above, first_over = within_budget(points, budget)
    head = f"at most {budget:g} ms ({hz} Hz)"
    if largest is None:
        return f"{head} at no measured count ({above}: {frames[above]:.3f} ms)"
    if above is None:
        return f"{head} at every measured count, up to {largest} quads"
    text = f"{head} up to {largest} quads ({above}: {frames[above]:.3f} ms)"
    if first_over is not None and first_over < largest:
        text += f", though over it at {first_over}"
    return text


def section_seed001_composited(runs):
    """Seed 001 Figs. 5.3.E-F: composited translucent shadows (sec. 4.2.3) against the quad count,
    from the specs seed001-composited-fine (0-30 quads, step 1) and seed001-composited-coarse
    (0-2000), both in assets/bench/seed001-composited.json. Within each run: the frame and the
    per-quad loop ('translucent draws', the seed's one scope, sec. 5.3.1) at a few counts and
    against translucent-shadows' frame; the largest count inside a 60 Hz and a 30 Hz frame, against
    the seed's 'real time only for single-digit counts'; and the exponent of the loop's time in the
    quad count, which the seed's partition (every quad a partition of its own: two passes per quad,
    each drawing the quads nearer the light) puts at about 2."""
    out = ["\n## Seed 001: composited translucent shadows on glass-field, against the quad count (Figs. 5.3.E-F)\n"]
    t = Table(["spec", "quads", "frame ms", "translucent draws ms", "translucent-shadows frame ms",
               "frame / translucent-shadows"],
              ["---", "---:", "---:", "---:", "---:", "---:"])
    bullets = []
    for source, s in runs.items():
        fine = results.where(s, spec="seed001-composited-fine")
        coarse = results.where(s, spec="seed001-composited-coarse")
        # translucent-shadows at the same count, same run (file): the fine spec's own rows, else
        # seed001-timing's (every 20 quads: every coarse count) where the run holds both specs.
        # assets/bench/seed001-composited.json is a run of its own, so its coarse rows above 30
        # quads have no ratio: every ratio here is within one run.
        against = {}
        for spec in ("seed001-timing", "seed001-composited-fine"):
            for r in results.where(s, spec=spec, technique="translucent-shadows"):
                against[quads(r)] = r
        for spec, rows, shown in (("fine", fine, lambda c: c in COMPOSITED_FINE_COUNTS),
                                  ("coarse", coarse, lambda c: c % 500 == 0)):
            for r in sorted(results.where(rows, technique=COMPOSITED), key=lambda r: quads(r) or 0):
                count = quads(r)
                if count is None or not shown(count):
                    continue
                base = against.get(count)
                t.add(source, [spec, count, ms(r, "frame_ms"), ms(r, "translucent_draws_ms"),
                               ms(base, "frame_ms"),
                               quotient(r["frame_ms"], base["frame_ms"], "{:.2f}x") if base else "n/a"])
        # Every measured count; at a count both specs measured (0), the fine spec's row (60 timed
        # frames, the coarse spec's 2).
        frames = {}
        for r in results.where(coarse, technique=COMPOSITED) + results.where(fine, technique=COMPOSITED):
            if quads(r) is not None and results.number(r.get("frame_ms")) is not None:
                frames[quads(r)] = r["frame_ms"]
        if frames:
            points = sorted(frames.items())
            largest, above, _ = within_budget(points, FRAME_BUDGETS[0][1])
            if largest is None:
                verdict = "here not even 0 quads at 60 Hz"
            elif above is None:
                verdict = f"here every measured count at 60 Hz, up to {largest}: the sweep ends first"
            elif largest < 10:
                verdict = "single-digit here too"
            else:
                verdict = f"here {largest} quads at 60 Hz"
            bullets.append((source, f"{COMPOSITED}: frame "
                            + ", ".join(budget_text(points, hz, budget) for hz, budget in FRAME_BUDGETS)
                            + f"; seed 001 sec. 5.3.1 (RTX 3070): real time only for single-digit counts, {verdict}"))
        draws = [(quads(r), results.number(r.get("translucent_draws_ms")))
                 for r in results.where(coarse, technique=COMPOSITED)]
        exponent, n = loglog_exponent(draws)
        if exponent is not None:
            used = sorted(c for c, y in draws if c is not None and c >= EXPONENT_MIN_QUADS and y and y > 0)
            bullets.append((source, f"translucent draws ms grows as quads^{exponent:.2f} (log-log least squares "
                            f"over the coarse spec's {n} counts {used[0]}-{used[-1]}; seed 001 sec. 4.2.3's "
                            "partition, two passes per quad each drawing the quads nearer the light, predicts "
                            "about 2)"))
    if t.rows:
        out += t.lines()
    if bullets:
        several = len({source for source, _ in bullets}) > 1
        out += [""] + [f"- {os.path.basename(source) + ': ' if several else ''}{line}" for source, line in bullets]
    return out, [t]


def report(rows):
    """The Markdown text of every section for the rows (results.load)."""
    runs = results.by_source(rows)
    lines, seen = [], []
    for source, items in runs.items():
        env = (items[0].get("gpu"), items[0].get("driver"), items[0].get("commit"))
        if env not in seen:
            seen.append(env)
            lines.append(results.run_line(items[0]))
    lines.append("")
    note = results.gbuffer_note(rows)
    if note:
        lead = "Every row was " + note if note == results.gbuffer_note([{"technique": "x", "gbuffer_every_frame": True}]) \
            else note[0].upper() + note[1:]
        lines.append(f"{lead} (a bench from before `frame_ms`): the accuracy G-buffer was written in every timed "
                     "frame, so their frame and main-pass times include it.\n")
    body, tables = [], []
    for section in (section_depth_floor, section_overhead, section_cpu, section_triangles, section_kernels,
                    section_fig415, section_light_size, section_fast_passes, section_seed001,
                    section_seed001_composited):
        text, made = section(runs)
        if any(t.rows for t in made):
            body += text
            tables += made
    if any(t.daggers for t in tables):
        lines.append(DAGGER_NOTE)
    text = "\n".join(lines + body) + "\n"
    while "\n\n\n" in text:          # a section left out leaves no gap of two lines
        text = text.replace("\n\n\n", "\n\n")
    return text


def main(argv=None):
    parser = argparse.ArgumentParser(prog="ratios.py", description="The project's ratios (Markdown) from "
                                     "shadowlab bench results; every ratio within one file (one run).")
    parser.add_argument("inputs", nargs="+", metavar="RESULTS", help="results files (.json or .csv)")
    parser.add_argument("--out", metavar="DIR", help="write DIR/ratios.md instead of printing")
    args = parser.parse_args(sys.argv[1:] if argv is None else argv)
    try:
        rows = results.load(args.inputs)
    except (OSError, ValueError) as e:
        print(f"ratios.py: {e}", file=sys.stderr)
        return 1
    text = report(rows)
    if args.out:
        print(results.write_text(text, args.out, "ratios.md"))
    else:
        sys.stdout.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
