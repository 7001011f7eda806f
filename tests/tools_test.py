#!/usr/bin/python3
"""Tests of the result tools (tools/results.py, charts.py, ratios.py, table41.py, stress_chart.py, strip.py), run by ctest.

    python3 tests/tools_test.py [-v]

A small synthetic fixture, written here, holds old-style rows (gpu_frame_ms, no G-buffer flag) and
new-style rows (frame_ms, shadow_term_ms, floors, gbuffer_every_frame), as JSON and as CSV. The
tools also run end to end on the committed GPU results in docs/results/h100-2026-11-25/*.json.
Seed 001's specs (assets/bench/seed001.json) have a synthetic fixture of their own, with an N^2
composited-translucent loop (Seed001Composited).
Outputs go to a temporary directory. Needs python3-matplotlib: when the interpreter that runs this
file lacks it (a pyenv or venv python3 first on PATH), the file runs itself again with
/usr/bin/python3, the interpreter Debian's python3-matplotlib belongs to (as shadowlab report does).
"""
import contextlib
import glob
import io
import json
import os
import subprocess
import sys
import tempfile
import unittest
from concurrent.futures import ThreadPoolExecutor

try:
    import matplotlib  # noqa: F401
except ImportError:
    if os.path.exists("/usr/bin/python3") and os.path.realpath(sys.executable) != os.path.realpath("/usr/bin/python3") \
            and not os.environ.get("SHADOWLAB_TOOLS_TEST_REEXEC"):
        os.environ["SHADOWLAB_TOOLS_TEST_REEXEC"] = "1"
        os.execv("/usr/bin/python3", ["/usr/bin/python3"] + sys.argv)
    raise

ROOT = os.path.dirname(os.path.dirname(os.path.realpath(__file__)))
TOOLS = os.path.join(ROOT, "tools")
RESULTS = os.path.join(ROOT, "docs", "results", "h100-2026-11-25")
H200 = os.path.join(ROOT, "docs", "results", "h200-2026-12-02-issue10")   # issue 10's latest run
sys.path.insert(0, TOOLS)
import results  # noqa: E402
import charts  # noqa: E402
import ratios  # noqa: E402
import table41  # noqa: E402
import stress_chart  # noqa: E402
from matplotlib.collections import PathCollection  # noqa: E402
from matplotlib.markers import MarkerStyle  # noqa: E402

ENV = {"gpu": "Test GPU", "driver": "test 1.0", "date": "2026-12-01T00:00:00Z", "commit": "abc123", "backend": "egl"}


def old_row(technique, scene="box", width=1920, height=1080, frame=None, main=None, passes=0.0, **extra):
    """A row as benches before `frame_ms` wrote it."""
    row = dict(ENV, technique=technique, scene=scene, width=width, height=height, pixels=width * height,
               triangles=extra.pop("triangles", 1000), light_size=0.5, cpu_frame_ms=0.1, gpu_technique_ms=passes)
    if frame is not None:
        row["gpu_frame_ms"] = frame
    if main is not None:
        row["gpu_main_ms"] = main
    row.update(extra)
    return row


def depth_floor(scene, resolution, ms, **extra):
    return old_row("depth-floor", scene, frame=ms + 0.001, passes=ms, gpu_depth_floor_ms=ms,
                   **dict({"param.resolution": resolution}, **extra))


def old_rows():
    rows = [
        old_row("none", frame=2.0, main=2.0, hard_mae=0.2, soft_mae=0.21, soft_mae_penumbra=0.5),
        old_row("shadowmap", frame=2.5, main=2.05, passes=0.4, gpu_shadow_map_ms=0.4, hard_mae=0.010,
                soft_mae=0.02, soft_mae_penumbra=0.30, **{"param.resolution": "1024", "param.kernel": "1"}),
        old_row("shadowmap", frame=3.2, main=2.06, passes=1.1, gpu_shadow_map_ms=1.1, hard_mae=0.004,
                soft_mae=0.02, soft_mae_penumbra=0.28, **{"param.resolution": "2048", "param.kernel": "1"}),
        old_row("pcf", frame=4.0, main=3.5, passes=0.4, hard_mae=0.012, soft_mae=0.01, soft_mae_penumbra=0.20,
                **{"param.resolution": "1024", "param.kernel": "3"}),
        old_row("pcf", frame=9.0, main=8.5, passes=0.4, hard_mae=0.015, soft_mae=0.008, soft_mae_penumbra=0.12,
                **{"param.resolution": "1024", "param.kernel": "7"}),
        old_row("pcss", frame=30.0, main=20.0, passes=9.0, hard_mae=0.003, soft_mae=0.004, soft_mae_penumbra=0.05,
                **{"param.resolution": "2048"}),
        depth_floor("box", 1024, 0.35),
        depth_floor("box", 2048, 1.0),
        # A scene sweep: dense over scene.segments (triangles grow), none, shadowmap and the floor.
    ]
    for segments, triangles, base in ((8, 40000, 3.0), (16, 190000, 3.4), (32, 790000, 4.0), (64, 3200000, 6.5)):
        s = {"scene.segments": float(segments), "triangles": triangles}
        rows.append(old_row("none", "dense", frame=base, main=base, **s))
        rows.append(old_row("shadowmap", "dense", frame=base * 1.3, main=base + 0.01, passes=base * 0.3,
                            gpu_shadow_map_ms=base * 0.3, **dict(s, **{"param.resolution": "2048"})))
        rows.append(depth_floor("dense", 2048, base * 0.28, **s))
    # Another scene with a different triangle count: must never join the dense sweep.
    rows.append(old_row("none", "forest", frame=7.0, main=7.0, triangles=240002))
    rows.append(old_row("shadowmap", "forest", frame=8.0, main=7.01, passes=1.0, gpu_shadow_map_ms=1.0,
                        triangles=240002, **{"param.resolution": "2048"}))
    # Table 4.1 rows (seed000.json's table41-* sweeps), enough for every cell of two columns.
    for technique, hw, precise, pen, noise_h, noise_s, false_shadow in (
            ("shadowmap", "false", 0.0016, 0.0, 0.0006, 0.0012, 0.0008),
            ("shadowmap", "true", 0.0023, 0.003, 0.0004, 0.0009, 0.0008),
            ("pcf", None, 0.004, 0.007, 0.0007, 0.0008, 0.0008)):
        p = {"param.hardware_filter": hw} if hw else {}
        rows.append(old_row(technique, "dragon-like", 1280, 720, 1.0, 1.0, spec="table41-precise",
                            hard_mae_outside_penumbra=precise, **p))
        rows.append(old_row(technique, "contact", 1280, 720, 1.0, 1.0, spec="table41-soft",
                            technique_penumbra_fraction=pen, soft_noise=noise_s, **p))
        rows.append(old_row(technique, "cube", 1280, 720, 1.0, 1.0, spec="table41-aliasing", hard_noise=noise_h, **p))
        rows.append(old_row(technique, "pillars", 1280, 720, 1.0, 1.0, spec="table41-grazing",
                            hard_false_shadow=false_shadow, **p))
        for height, share in ((0.5, pen), (2.0, pen * 1.6)):
            rows.append(old_row(technique, "hover", 1280, 720, 1.0, 1.0, spec="table41-contact",
                                technique_penumbra_fraction=share, **dict(p, **{"scene.height": height})))
    return rows


def new_row(technique, scene="box", frame=1.0, main=1.0, passes=0.0, term=0.0, **extra):
    """A row as the bench writes it from `frame_ms` on."""
    row = dict(ENV, technique=technique, scene=scene, width=1280, height=720, pixels=1280 * 720,
               triangles=extra.pop("triangles", 1000), light_size=0.5, frame_ms=frame, main_ms=main,
               technique_passes_ms=passes, shadow_term_ms=term, floor_main_ms=extra.pop("floor_main", 0.9),
               cpu_frame_ms=0.05, cpu_wait_ms=0.01, gbuffer_every_frame=False, gpu_bytes=4194304)
    row.update(extra)
    return row


def new_rows():
    rows = [
        new_row("none", frame=0.9, main=0.9, hard_mae=0.2, soft_mae=0.2, soft_mae_penumbra=0.45,
                soft_reference_floor=0.01, soft_reference_rays=256),
        new_row("shadowmap", frame=1.2, main=0.95, passes=0.25, term=0.05, floor_depth_ms=0.2, gpu_shadow_map_ms=0.25,
                hard_mae=0.004, soft_mae=0.02, soft_mae_penumbra=0.3, soft_reference_floor=0.01,
                soft_reference_rays=256, **{"param.resolution": "2048"}),
        new_row("pcss", frame=12.0, main=9.0, passes=3.0, term=8.1, floor_depth_ms=0.2, hard_mae=0.003,
                soft_mae=0.004, soft_mae_penumbra=0.04, soft_reference_floor=0.012, soft_reference_rays=256,
                **{"param.resolution": "2048"}),
        new_row("csm", frame=1.6, main=1.0, passes=0.6, term=0.1, hard_mae=0.002, soft_mae=0.02,
                soft_mae_penumbra=0.3, soft_reference_floor=0.01, soft_reference_rays=256, **{"param.cascades": "4"}),
        new_row("brand-new-technique", frame=2.0, main=1.0, passes=1.0, term=0.1, hard_mae=0.05, soft_mae=0.05,
                soft_mae_penumbra=0.35, soft_reference_floor=0.01, soft_reference_rays=256),
    ]
    # A scene.count sweep of the forest (the new bench's triangle scaling): one scene, two techniques.
    for count, base in ((100, 1.0), (1000, 2.0), (10000, 12.0)):
        s = {"scene.count": count, "triangles": count * 48}
        rows.append(new_row("none", "forest", frame=base, main=base, floor_main=base, **s))
        rows.append(new_row("shadowmap", "forest", frame=base * 1.5, main=base + 0.02, passes=base * 0.4, term=0.02,
                            floor_main=base, floor_depth_ms=base * 0.45, **dict(s, **{"param.resolution": "2048"})))
    return rows


def write_csv(rows, path):
    """The bench's CSV: columns in first-seen order, strings raw, other values as JSON."""
    columns = []
    for row in rows:
        for key in row:
            if key not in columns:
                columns.append(key)
    with open(path, "w") as f:
        f.write(",".join(columns) + "\n")
        for row in rows:
            cells = []
            for c in columns:
                if c not in row:
                    cells.append("")
                    continue
                v = row[c]
                text = v if isinstance(v, str) else json.dumps(v)
                cells.append('"' + text.replace('"', '""') + '"' if any(ch in text for ch in ',"\n') else text)
            f.write(",".join(cells) + "\n")


def run_tool(name, *args):
    """The tool as a user runs it: a process of its own."""
    return subprocess.run([sys.executable, os.path.join(TOOLS, name), *args], capture_output=True, text=True,
                          timeout=300)


def call(module, *args):
    """The tool's main(argv) in this process (matplotlib imported once): (exit code, stdout)."""
    out = io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(io.StringIO()):
        try:
            rc = module.main(list(args))
        except SystemExit as e:          # argparse: --help, usage errors
            rc = e.code
    return rc, out.getvalue()


def marker_vertices(marker):
    style = MarkerStyle(marker)
    return style.get_path().transformed(style.get_transform()).vertices.round(6).tolist()


class Fixture(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory(prefix="shadowlab-tools-test-")
        cls.dir = cls.tmp.name
        cls.old_path = os.path.join(cls.dir, "old.json")
        cls.new_path = os.path.join(cls.dir, "new.json")
        cls.csv_path = os.path.join(cls.dir, "new.csv")
        with open(cls.old_path, "w") as f:
            json.dump(old_rows(), f)
        with open(cls.new_path, "w") as f:
            json.dump(new_rows(), f)
        write_csv(new_rows(), cls.csv_path)
        # The longest job, charts of every committed result, runs in a process of its own from the
        # start, on the second core, while the other tests run here.
        cls.committed = os.path.join(cls.dir, "committed")
        cls.committed_files = sorted(glob.glob(os.path.join(RESULTS, "*.json")))
        cls.pool = ThreadPoolExecutor(max_workers=1)
        cls.committed_charts = cls.pool.submit(run_tool, "charts.py", *cls.committed_files, "--out",
                                               os.path.join(cls.committed, "charts"), "--dpi", "40")

    @classmethod
    def tearDownClass(cls):
        cls.pool.shutdown(wait=True)
        cls.tmp.cleanup()

    # --- loader -------------------------------------------------------------------------------
    def test_old_rows_normalised_and_flagged(self):
        rows = results.load(self.old_path)
        sm = results.first(rows, technique="shadowmap", scene="box", **{"param.resolution": 2048})
        self.assertEqual(sm["frame_ms"], 3.2)
        self.assertEqual(sm["technique_passes_ms"], 1.1)
        self.assertEqual(sm["main_ms"], 2.06)
        self.assertIs(sm["gbuffer_every_frame"], True)
        # The shadow term: main with the technique minus main with none, same file, scene and size.
        self.assertAlmostEqual(sm["shadow_term_ms"], 0.06)
        self.assertTrue(results.derived(sm, "shadow_term_ms"))
        self.assertTrue(results.derived_from_gbuffer(sm, "shadow_term_ms"))
        self.assertEqual(sm["floor_main_ms"], 2.0)
        # The depth floor of the same scene, size and resolution (an int there, a string here).
        self.assertEqual(sm["floor_depth_ms"], 1.0)
        self.assertTrue(results.derived(sm, "floor_depth_ms"))
        floor = results.first(rows, technique="depth-floor", scene="box", **{"param.resolution": "1024"})
        self.assertEqual(floor["floor_depth_ms"], 0.35)
        # Each dense step gets its own step's none, not another step's.
        dense = results.first(rows, technique="shadowmap", scene="dense", **{"scene.segments": 16})
        self.assertAlmostEqual(dense["shadow_term_ms"], 0.01)
        self.assertEqual(results.gbuffer_note(rows), "measured with the G-buffer on every frame")

    def test_new_rows_json_and_csv(self):
        for path in (self.new_path, self.csv_path):
            rows = results.load(path)
            sm = results.first(rows, technique="shadowmap", scene="box")
            self.assertIs(sm["gbuffer_every_frame"], False, path)
            self.assertEqual(sm["shadow_term_ms"], 0.05, path)
            self.assertFalse(results.derived(sm, "shadow_term_ms"), path)
            self.assertFalse(results.derived(sm, "floor_depth_ms"), path)
            self.assertEqual(results.canonical(sm["param.resolution"]), "2048", path)
            self.assertEqual(sm["cpu_wait_ms"], 0.01, path)
            self.assertEqual(results.gbuffer_note(rows), "", path)
        # A row with frame_ms and no flag is a new-style row; one without frame_ms is old.
        self.assertIs(results.normalise([{"technique": "x", "frame_ms": 1.0}])[0]["gbuffer_every_frame"], False)
        self.assertIs(results.normalise([{"technique": "x", "gpu_frame_ms": 1.0}])[0]["gbuffer_every_frame"], True)
        both = results.load([self.old_path, self.new_path])
        self.assertEqual(len(results.by_source(both)), 2)
        self.assertIn("of", results.gbuffer_note(both))

    def test_no_derivation_across_files(self):
        # A row whose view (scene, size) has a `none` row in another file only: no shadow term.
        other = os.path.join(self.dir, "other.json")
        with open(other, "w") as f:
            json.dump([old_row("shadowmap", frame=3.0, main=2.5, passes=0.5, **{"param.resolution": "2048"})], f)
        rows = results.load([self.old_path, other])
        lone = [r for r in rows if r["_source"] == other][0]
        self.assertNotIn("shadow_term_ms", lone)

    # --- helpers ------------------------------------------------------------------------------
    def test_pareto_front(self):
        pts = [(1, 5), (2, 3), (3, 4), (4, 1), (2, 3.5), (5, 1), (0.5, None)]
        rows = [{"x": x, "y": y} for x, y in pts]
        front = [(r["x"], r["y"]) for r in results.pareto_front(rows, "x", "y")]
        self.assertEqual(front, [(1, 5), (2, 3), (4, 1)])

    def test_log_scale_decision(self):
        self.assertFalse(results.use_log([1.0, 10.0]))
        self.assertTrue(results.use_log([1.0, 10.5]))
        self.assertTrue(results.use_log([0.0, 0.01, 5.0]))     # zeros do not count
        self.assertFalse(results.use_log([3.0]))
        self.assertFalse(results.use_log([0.0, 0.0]))

    def test_styles_fixed(self):
        ids = ["none", "planar", "shadowmap", "pcf", "adaptive-pcf", "vsm", "esm", "evsm", "msm", "pcss",
               "area-reference", "reference", "depth-floor", "csm", "psm", "lispsm", "tsm", "stochastic-sm",
               "cssm2", "translucent-shadows", "composited-translucent"]
        for technique in ids:
            self.assertIn(technique, results.STYLE)
        self.assertEqual(len(set(results.STYLE.values())), len(results.STYLE), "two techniques share a style")
        for plugin in os.listdir(os.path.join(ROOT, "plugins")):
            if os.path.isdir(os.path.join(ROOT, "plugins", plugin)):
                self.assertIn(plugin, results.STYLE, f"plugins/{plugin} has no fixed style")
        # Unknown ids: a style from the fallback tables, the same in every process (no salted hash()).
        colour, marker = results.style("brand-new-technique")
        self.assertIn(colour, results.FALLBACK_COLOURS)
        self.assertIn(marker, results.FALLBACK_MARKERS)
        code = "import sys; sys.path.insert(0, sys.argv[1]); import results; print(results.style('brand-new-technique'))"
        for seed in ("1", "2"):
            other = subprocess.run([sys.executable, "-c", code, TOOLS], capture_output=True, text=True,
                                   env=dict(os.environ, PYTHONHASHSEED=seed))
            self.assertEqual(other.stdout.strip(), str((colour, marker)))

    def test_param_string_only_varying(self):
        rows = [r for r in results.load(self.old_path) if r.get("scene") == "box" and r["technique"] == "pcf"]
        keys = results.label_keys(rows)
        self.assertEqual(keys, ["param.kernel"])
        self.assertEqual(results.label(rows[0], keys), "pcf kernel=3")

    def test_scene_sweeps_one_scene_each(self):
        rows = results.load([self.old_path, self.new_path])
        sweeps = [s for s in results.scene_sweeps(rows) if s["scene"] in ("dense", "forest")]
        self.assertEqual([(s["scene"], s["keys"]) for s in sweeps],
                         [("dense", ["scene.segments"]), ("forest", ["scene.count"])])
        for s in sweeps:
            self.assertEqual({r["scene"] for r in s["rows"]}, {s["scene"]})
            self.assertEqual({r["_source"] for r in s["rows"]}, {s["rows"][0]["_source"]})

    # --- charts -------------------------------------------------------------------------------
    def test_pareto_styles_none_and_labels(self):
        rows = results.load(self.old_path)
        box = results.by_scene_size(results.techniques(rows, ("depth-floor",)))[("box", (1920, 1080))]
        styles = []
        for kind in ("hard", "soft"):
            fig, info = charts.pareto_figure(box, "box", (1920, 1080), kind)
            ax = fig.axes[0]
            seen = {}
            for c in ax.collections:
                if isinstance(c, PathCollection) and c.get_label() in results.STYLE:
                    colour = matplotlib.colors.to_hex(c.get_facecolor()[0])
                    seen[c.get_label()] = (colour, c.get_paths()[0].vertices.round(6).tolist())
            self.assertNotIn("none", seen, "none must be a reference line, not a point")
            lines = [ln.get_label() for ln in ax.get_lines()]
            self.assertTrue(any(label.startswith("none:") for label in lines), lines)
            for technique, (colour, vertices) in seen.items():
                self.assertEqual(colour, results.style(technique)[0])
                self.assertEqual(vertices, marker_vertices(results.style(technique)[1]))
            texts = [t.get_text() for t in ax.texts]
            self.assertEqual(len(texts), len(info["front"]))   # every front point labelled
            self.assertIn("G-buffer", ax.get_title())
            styles.append(seen)
            if kind == "soft":
                self.assertEqual(info["y"], "soft_mae_penumbra")
                self.assertIn("penumbra", ax.get_ylabel())
                self.assertIn("pcf kernel=3", texts)
                self.assertEqual(texts[-1], "pcss")
            else:
                self.assertEqual(info["y"], "hard_mae")
                self.assertEqual(info["scales"], ("log", "linear"))   # 2 to 30 ms; errors 0.003 to 0.015
                self.assertEqual(texts, ["shadowmap resolution=1024", "shadowmap resolution=2048", "pcss"])
            matplotlib.pyplot.close(fig)
        common = set(styles[0]) & set(styles[1])
        self.assertGreaterEqual(len(common), 3)
        for technique in common:
            self.assertEqual(styles[0][technique], styles[1][technique])

    def test_soft_chart_reference_floor_and_new_rows(self):
        rows = results.load(self.new_path)
        box = results.by_scene_size(rows)[("box", (1280, 720))]
        fig, info = charts.pareto_figure(box, "box", (1280, 720), "soft")
        ax = fig.axes[0]
        self.assertEqual(info["floor"], 0.01)
        self.assertTrue(any("sampling error (256 rays)" in ln.get_label() for ln in ax.get_lines()))
        self.assertNotIn("G-buffer", ax.get_title())
        self.assertEqual(info["scales"][1], "log")               # 0.01 (floor) to 0.35
        labels = {c.get_label() for c in ax.collections}
        self.assertIn("brand-new-technique", labels)
        matplotlib.pyplot.close(fig)

    def test_sweep_chart_uses_same_styles(self):
        rows = [r for r in results.load(self.old_path) if r.get("scene") == "box"]
        fig, info = charts.against_figure(results.techniques(rows, ("depth-floor",)), "param.resolution", "box",
                                          "resolution", base=2)
        for line in fig.axes[0].get_lines():
            technique = info["series"][line.get_label()][0]
            self.assertEqual(matplotlib.colors.to_hex(line.get_color()), results.style(technique)[0])
            self.assertEqual(line.get_marker(), results.style(technique)[1])
        matplotlib.pyplot.close(fig)

    def test_triangles_chart_one_scene(self):
        rows = results.load([self.old_path, self.new_path])
        checked = []
        for sweep in results.scene_sweeps(rows):
            if sweep["scene"] not in ("dense", "forest"):
                continue
            checked.append(sweep["scene"])
            made = charts.triangles_figure(sweep)
            self.assertIsNotNone(made, sweep["scene"])
            fig, info = made
            self.assertEqual(info["scenes"], [sweep["scene"]])
            xs = {x for _, pts in info["series"].values() for x, _ in pts}
            wanted = {results.number(r["triangles"]) for r in sweep["rows"]}
            self.assertEqual(xs, wanted)
            self.assertNotIn(240002.0, xs)                     # the old file's lone forest rows
            techniques = sorted(t for t, _ in info["series"].values())
            self.assertEqual(len(techniques), len(set(techniques)), "one line per technique")
            self.assertEqual(info["scales"][0], "log")
            matplotlib.pyplot.close(fig)
        self.assertEqual(checked, ["dense", "forest"])

    # --- end to end ---------------------------------------------------------------------------
    def test_tools_end_to_end_on_fixture(self):
        out = os.path.join(self.dir, "out")
        inputs = [self.old_path, self.csv_path]
        helped = run_tool("charts.py", "--help")
        self.assertEqual(helped.returncode, 0, helped.stderr)
        self.assertIn("--out DIR", helped.stdout)
        for module in (ratios, table41):
            rc, text = call(module, "--help")
            self.assertEqual(rc, 0)
            self.assertIn("--out DIR", text)
        rc, printed = call(charts, *inputs, "--out", os.path.join(out, "charts"), "--dpi", "40")
        self.assertEqual(rc, 0)
        names = sorted(os.path.basename(p) for p in printed.split())
        for p in printed.split():
            with open(p, "rb") as f:
                self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n", p)
        for name in ("pareto-box-1920x1080-hard.png", "pareto-box-1920x1080-soft.png", "pareto-box-1280x720-soft.png",
                     "sweep-resolution-box.png", "sweep-kernel-box.png", "triangles-dense.png",
                     "triangles-forest.png"):
            self.assertIn(name, names)
        self.assertFalse([n for n in names if n.startswith("triangles-all")])
        self.assertFalse([n for n in names if n.startswith("seed001-")])    # no seed 001 rows, no seed 001 charts
        # The older form, as shadowlab report calls it (a process of its own, its stdout the list).
        legacy = run_tool("charts.py", self.new_path, os.path.join(out, "legacy"), "--dpi", "40")
        self.assertEqual(legacy.returncode, 0, legacy.stderr)
        self.assertIn(os.path.join(out, "legacy", "pareto-box-1280x720-hard.png"), legacy.stdout.split())
        self.assertTrue(os.path.isfile(os.path.join(out, "legacy", "pareto-box-1280x720-hard.png")))

        done = run_tool("ratios.py", *inputs, "--out", out)
        self.assertEqual(done.returncode, 0, done.stderr)
        with open(os.path.join(out, "ratios.md")) as f:
            text = f.read()
        self.assertIn("shadow term ms", text)
        self.assertIn("technique passes ms", text)
        self.assertIn("CPU wait ms", text)
        self.assertIn(ratios.DAGGER, text)                     # the old file's derived terms
        self.assertIn("## Time against triangle count (dense, scene.segments swept, 1920x1080)", text)
        self.assertIn("## Time against triangle count (forest, scene.count swept, 1280x720)", text)
        self.assertIn("| 4,800 | 1.000 | 1.500 | n/a | 0.450 | 0.020 | 0.89x |", text)   # new rows: no dagger
        self.assertIn("G-buffer on every frame", text)
        self.assertIn("| file |", text)                        # two files in the CPU table

        done = run_tool("table41.py", *inputs, "--out", out)
        self.assertEqual(done.returncode, 0, done.stderr)
        with open(os.path.join(out, "table41.md")) as f:
            text = f.read()
        self.assertIn("| Precise shadows | Yes (0.0016) | Yes (0.0023) | ~ (0.004) |", text)
        rc, _ = call(table41, self.new_path)                   # no table41-* rows: an error, not n/a
        self.assertEqual(rc, 1)

    def test_tools_on_committed_results(self):
        # Sorted after the fixture tests (unittest runs them by name): its charts run meanwhile.
        files = self.committed_files
        self.assertTrue(files)
        out = self.committed
        for module, args in ((ratios, [os.path.join(RESULTS, "default.json"), os.path.join(RESULTS, "seed000.json"),
                                       "--out", out]),
                             (table41, [os.path.join(RESULTS, "seed000.json"), "--out", out]),
                             (table41, files + ["--out", os.path.join(out, "all")]),
                             (ratios, files + ["--out", os.path.join(out, "all")])):
            self.assertEqual(call(module, *args)[0], 0, (module.__name__, args))
        done = self.committed_charts.result()
        self.assertEqual(done.returncode, 0, done.stderr)
        charts_made = done.stdout.split()
        self.assertGreater(len(charts_made), 40)
        for p in charts_made:
            self.assertGreater(os.path.getsize(p), 1000, p)
        names = {os.path.basename(p) for p in charts_made}
        for name in ("pareto-cube-1920x1080-hard.png", "pareto-dragon-like-1920x1080-soft.png",
                     "sweep-kernel-cube.png", "sweep-resolution-forest.png", "resolution-cube.png",
                     "triangles-dense-default.png", "triangles-dense-default-before-instancing.png"):
            self.assertIn(name, names)
        self.assertFalse([n for n in names if n.startswith("triangles-") and "dense" not in n], names)
        # Every chart (at 40 dpi here) keeps its legend and labels off the points.
        labelled = 0
        for p in charts_made:
            with open(os.path.splitext(p)[0] + ".boxes.json") as f:
                boxes = json.load(f)
            self.assertEqual(charts.box_problems(boxes), [], p)
            labelled += len(boxes["labels"])
        self.assertGreater(labelled, 50)
        with open(os.path.join(out, "ratios.md")) as f:
            text = f.read()
        for heading in ("## Shadow pass against the depth-only floor", "## Frame-time overhead of shadowmap",
                        "## Host CPU time per frame", "## Time against triangle count (dense, scene.segments swept",
                        "## Adaptive PCF against PCF", "## VSM with twice the kernel",
                        "## Every technique at 1024 map", "## PCSS against light size"):
            self.assertIn(heading, text)
        self.assertIn("| cube | 2048 | 0.445 | 0.458 | 1.03x |", text)   # unchanged from ratios.md
        with open(os.path.join(RESULTS, "table41.md")) as f:
            committed = f.read().split("\n\n")[0].strip()
        with open(os.path.join(out, "table41.md")) as f:
            self.assertEqual(f.read().strip(), committed)
        for name in ("table41.md", "ratios.md"):
            self.assertGreater(os.path.getsize(os.path.join(out, "all", name)), 1000)

    def test_fast_pass_sections_reproduce_the_committed_ratios(self):
        # ratios.md of the H200 run is this tool's output on its five files, fast-pass tables included.
        inputs = [os.path.join(H200, name) for name in ("default.json", "default-rest.json", "seed000.json",
                                                        "seed000-rest.json", "fast-passes.json")]
        rc, text = call(ratios, *inputs)
        self.assertEqual(rc, 0)
        for heading in ("## Moment techniques: their passes against the depth-only floor",
                        "## PCF: gather and folded against the tap loop", "## Host depth pre-pass on forest",
                        "PCSS's sample grids on forest"):
            self.assertIn(heading, text)
        self.assertNotIn("| depth-floor |", text.split("## Moment techniques")[1].split("## PCF")[0])
        self.assertIn("| pcf (sampling = taps) | 10.203 | 5.198 | 1.62x | 1.552 | 1.184 |", text)   # the pre-pass on forest
        self.assertIn("| cube | 11 | false | true | 6.421 | 4.154 | 0.65x | 4.134 | 0.64x |", text)  # gather, folded against taps
        with open(os.path.join(H200, "ratios.md")) as f:
            self.assertEqual(f.read(), text)


class ChartBoxes(unittest.TestCase):
    """Issue 32: legends beside the axes, Pareto labels off every marker and each other, checked
    from the <chart>.boxes.json that charts.py writes beside each PNG (pixels of that PNG)."""

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory(prefix="shadowlab-chart-boxes-")
        # The H200 run whose contact soft chart had its legend over the worst cluster and
        # overlapping labels: 16 front points, seven of them within 0.5 ms and 10% of each other.
        inputs = [os.path.join(H200, "default.json"), os.path.join(H200, "fast-passes.json")]
        cls.made = run_tool("charts.py", *inputs, "--out", cls.tmp.name, "--dpi", "120")

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def boxes(self, name):
        with open(os.path.join(self.tmp.name, name + ".boxes.json")) as f:
            return json.load(f)

    def test_every_chart_keeps_its_legend_and_labels_off_the_points(self):
        self.assertEqual(self.made.returncode, 0, self.made.stderr)
        pngs = self.made.stdout.split()
        self.assertGreater(len(pngs), 10)
        for png in pngs:
            boxes = self.boxes(os.path.splitext(os.path.basename(png))[0])
            self.assertEqual(charts.box_problems(boxes), [], png)
            self.assertIsNotNone(boxes["legend"], png)
            self.assertGreaterEqual(boxes["legend"][0], boxes["axes"][2], f"{png}: the legend is not right of the axes")
            self.assertGreater(len(boxes["markers"]), 3, png)
        contact = self.boxes("pareto-contact-1920x1080-soft")
        self.assertGreaterEqual(len(contact["labels"]), 12)
        # The boxes are those of the PNG: its size in pixels.
        from PIL import Image
        with Image.open(os.path.join(self.tmp.name, "pareto-contact-1920x1080-soft.png")) as image:
            self.assertEqual(list(image.size), [round(v) for v in contact["figure"]])

    def test_the_check_sees_overlaps(self):
        # The placement before issue 32 (labels at a fixed offset, the legend inside the axes) on
        # the same chart: the check must find both, or it could not tell a good chart from a bad one.
        rows = results.load([os.path.join(H200, "default.json"), os.path.join(H200, "fast-passes.json")])
        contact = results.by_scene_size(results.techniques(rows, ("depth-floor",)))[("contact", (1920, 1080))]
        fig, info = charts.pareto_figure(contact, "contact", (1920, 1080), "soft")
        ax = fig.axes[0]
        self.assertEqual(charts.box_problems(charts.chart_boxes(fig)), [])
        for text in list(ax.texts):
            text.remove()
        keys = results.label_keys(contact)
        for i, row in enumerate(info["front"]):
            ax.annotate(results.label(row, keys), (row["frame_ms"], row[info["y"]]), fontsize=6,
                        xytext=(4, 4 if i % 2 == 0 else -9), textcoords="offset points")
        for legend in list(fig.legends):
            legend.remove()
        ax.legend(fontsize=7, ncol=2)
        problems = charts.box_problems(charts.chart_boxes(fig))
        matplotlib.pyplot.close(fig)
        self.assertTrue(any("covers a marker" in p for p in problems), problems)
        self.assertTrue(any(p.startswith("labels '") and p.endswith("overlap") for p in problems), problems)
        self.assertIn("the legend overlaps the axes", problems)


def seed001_row(spec, technique, quads, frame, passes, main, **extra):
    """A row of seed 001's specs (assets/bench/seed001.json, seed001-composited.json) on glass-field."""
    row = new_row(technique, "glass-field", frame=frame, main=main, passes=passes, term=0.01, floor_main=1.2,
                  spec=spec, width=1920, height=1080, pixels=1920 * 1080, frames=60, **{"scene.quads": float(quads)})
    row.update(extra)
    return row


def composited_draws(quads):
    """The synthetic per-quad loop of composited-translucent: N^2 draws (seed 001 sec. 5.3.1: two
    passes per quad, each drawing the quads nearer the light) plus a constant."""
    return 0.1 * quads * quads + 0.1


def seed001_timing_rows():
    """seed001.json's seed001-timing, synthetic and every 100 quads (the spec: every 20)."""
    rows = []
    for n in range(0, 2001, 100):
        rows.append(seed001_row("seed001-timing", "shadowmap", n, 1.8 + 0.00025 * n, 0.65, 1.17 + 0.00025 * n))
        rows.append(seed001_row("seed001-timing", "translucent-shadows", n, 3.0 + 0.0004 * n, 1.8, 1.2 + 0.0004 * n))
        rows.append(seed001_row("seed001-timing", "stochastic-sm", n, 7.9 + 0.0039 * n, 0.9, 7.0 + 0.0039 * n,
                                **{"param.kernel": "9"}))
        for kernel, base, slope in ((9, 11.3, 0.0048), (3, 4.5, 0.0012)):
            rows.append(seed001_row("seed001-timing", "cssm2", n, base + slope * n, 2.7, base - 2.7 + slope * n,
                                    **{"param.kernel": str(kernel)}))
    return rows


def seed001_composited_rows():
    """seed001-composited.json's two specs, synthetic, at the spec's counts. composited-translucent's
    frame is 3 ms + its loop: within 16.7 ms (60 Hz) up to 11 quads (15.2 ms; 12: 17.5) and within
    33.3 ms (30 Hz) up to 17 (32.0; 18: 35.5)."""
    rows = []
    for n in range(0, 31):
        rows.append(seed001_row("seed001-composited-fine", "shadowmap", n, 1.8 + 0.00025 * n, 0.65, 1.17))
        rows.append(seed001_row("seed001-composited-fine", "translucent-shadows", n, 3.0 + 0.0004 * n, 1.8, 1.2))
        d = composited_draws(n)
        rows.append(seed001_row("seed001-composited-fine", "composited-translucent", n, 3.0 + d, 1.8, 1.2 + d,
                                translucent_draws_ms=d))
    for n in list(range(0, 1001, 100)) + [1500, 2000]:
        d = composited_draws(n)
        rows.append(seed001_row("seed001-composited-coarse", "composited-translucent", n, 3.0 + d, 1.8, 1.2 + d,
                                frames=2, translucent_draws_ms=d))
    return rows


class Seed001Composited(unittest.TestCase):
    """Seed 001 Figs. 5.3.E-F (sec. 5.3.1): ratios.py's composited section and charts.py's two seed001
    charts on synthetic rows whose composited loop grows as N^2, in two files as the two spec files
    write them (seed001.json, seed001-composited.json) and in one."""

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory(prefix="shadowlab-seed001-test-")
        cls.timing = os.path.join(cls.tmp.name, "seed001.json")
        cls.composited = os.path.join(cls.tmp.name, "seed001-composited.json")
        cls.both = os.path.join(cls.tmp.name, "both.json")
        for path, rows in ((cls.timing, seed001_timing_rows()), (cls.composited, seed001_composited_rows()),
                           (cls.both, seed001_timing_rows() + seed001_composited_rows())):
            with open(path, "w") as f:
                json.dump(rows, f)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def rows_of(self, spec):
        return [r for r in results.load(self.composited)
                if r["spec"] == spec and r["technique"] == "composited-translucent"]

    def test_exponent_of_the_loop_near_two(self):
        draws = [(r["scene.quads"], r["translucent_draws_ms"]) for r in self.rows_of("seed001-composited-coarse")]
        exponent, n = ratios.loglog_exponent(draws)
        self.assertAlmostEqual(exponent, 2.0, delta=0.01)
        self.assertEqual(n, 12)                                # 100-1000, 1500, 2000: 0 quads is left out
        # A constant loop has exponent 0; one count is no fit.
        self.assertAlmostEqual(ratios.loglog_exponent([(100, 5.0), (1000, 5.0)])[0], 0.0)
        self.assertEqual(ratios.loglog_exponent([(0, 0.1), (50, 250.1), (100, 1000.1)]), (None, 1))

    def test_counts_within_60_and_30_hz(self):
        rows = self.rows_of("seed001-composited-fine") + self.rows_of("seed001-composited-coarse")
        points = sorted({r["scene.quads"]: r["frame_ms"] for r in rows}.items())
        self.assertEqual(ratios.within_budget(points, 16.7), (11, 12, 12))
        self.assertEqual(ratios.within_budget(points, 33.3), (17, 18, 18))
        # The fine spec ends at 30: a budget met there has the coarse spec's 100 as the next count.
        self.assertEqual(ratios.within_budget(points, 100.0)[:2], (30, 100))
        # A noisy curve: the largest count within budget is still the answer, the early miss said.
        noisy = [(0, 3.0), (1, 18.0), (2, 10.0), (3, 20.0)]
        self.assertEqual(ratios.within_budget(noisy, 16.7), (2, 3, 1))
        self.assertIn("though over it at 1", ratios.budget_text(noisy, 60, 16.7))
        self.assertIn("at no measured count (0: 20.000 ms)", ratios.budget_text([(0, 20.0), (1, 30.0)], 60, 16.7))
        self.assertIn("at every measured count, up to 1 quads", ratios.budget_text([(0, 2.0), (1, 3.0)], 60, 16.7))

    def test_ratios_section(self):
        rc, text = call(ratios, self.timing, self.composited)
        self.assertEqual(rc, 0)
        self.assertIn("## Seed 001: translucent casters on glass-field", text)       # Figs. 5.3.A-D, as before
        section = text.split("## Seed 001: composited translucent shadows on glass-field")[1]
        self.assertIn("| spec | quads | frame ms | translucent draws ms | translucent-shadows frame ms | "
                      "frame / translucent-shadows |", section)                        # one file: no file column
        counts = [line.split(" | ")[1] for line in section.splitlines() if line.startswith("| fine |")]
        self.assertEqual(counts, ["0", "1", "2", "5", "10", "20", "30"])
        self.assertIn("| fine | 10 | 13.100 | 10.100 | 3.004 | 4.36x |", section)
        counts = [line.split(" | ")[1] for line in section.splitlines() if line.startswith("| coarse |")]
        self.assertEqual(counts, ["0", "500", "1000", "1500", "2000"])
        # translucent-shadows at 500 quads is in the other file (run): no ratio across runs.
        self.assertIn("| coarse | 500 | 25003.100 | 25000.100 | n/a | n/a |", section)
        self.assertIn("| coarse | 0 | 3.100 | 0.100 | 3.000 | 1.03x |", section)   # the fine spec's, same file
        self.assertIn("at most 16.7 ms (60 Hz) up to 11 quads (12: 17.500 ms)", section)
        self.assertIn("at most 33.3 ms (30 Hz) up to 17 quads (18: 35.500 ms)", section)
        self.assertIn("real time only for single-digit counts, here 11 quads at 60 Hz", section)
        self.assertIn("translucent draws ms grows as quads^2.00", section)
        self.assertIn("12 counts 100-2000", section)
        # One run holding both spec files' rows: seed001-timing's translucent-shadows at 500.
        rc, text = call(ratios, self.both)
        self.assertIn("| coarse | 500 | 25003.100 | 25000.100 | 3.200 | 7813.47x |", text)
        # A curve within 60 Hz to 7 quads only: the seed's single digits.
        rows = results.load(self.composited)
        for r in rows:
            if r["technique"] == "composited-translucent":
                r["frame_ms"] = 3.1 + 0.25 * r["scene.quads"] ** 2
        lines, _ = ratios.section_seed001_composited(results.by_source(rows))
        self.assertIn("up to 7 quads (8: 19.100 ms)", "\n".join(lines))
        self.assertIn("single-digit here too", "\n".join(lines))
        # No composited rows, no section (and the Figs. 5.3.A-D section as before).
        rc, text = call(ratios, self.timing)
        self.assertEqual(rc, 0)
        self.assertIn("## Seed 001: translucent casters on glass-field", text)
        self.assertNotIn("composited", text)

    def test_charts_written(self):
        out = os.path.join(self.tmp.name, "charts")
        rc, printed = call(charts, self.timing, self.composited, "--out", out, "--dpi", "40")
        self.assertEqual(rc, 0)
        names = {os.path.basename(p): p for p in printed.split()}
        for name in ("seed001-quads.png", "seed001-composited-fine.png"):
            self.assertIn(name, names)
            self.assertGreater(os.path.getsize(names[name]), 1000, name)
            with open(names[name], "rb") as f:
                self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n", name)
        # Without the composited specs: the 0-2000 chart only.
        rc, printed = call(charts, self.timing, "--out", os.path.join(self.tmp.name, "timing"), "--dpi", "40")
        self.assertEqual(rc, 0)
        names = [os.path.basename(p) for p in printed.split()]
        self.assertIn("seed001-quads.png", names)
        self.assertNotIn("seed001-composited-fine.png", names)

    def test_quads_chart_lines_and_styles(self):
        # The two spec files' runs on one chart, each curve from one file.
        fig, info = charts.seed001_quads_figure(results.load([self.timing, self.composited]))
        self.assertEqual(list(info["series"]), ["shadowmap", "stochastic-sm 9x9", "cssm2 9x9", "cssm2 3x3",
                                                "translucent-shadows", "composited-translucent"])
        self.assertEqual(info["scales"], ("linear", "log"))   # 1.8 ms to 400 s: decades apart
        self.assertIn("rows of 2 files", fig.axes[0].get_title())
        self.assertIn("composited-translucent: 13 counts, 2 timed frames each", fig.axes[0].get_title())
        lines = {ln.get_label(): ln for ln in fig.axes[0].get_lines()}
        for text, (technique, points) in info["series"].items():
            self.assertEqual(matplotlib.colors.to_hex(lines[text].get_color()), results.style(technique)[0])
            self.assertEqual(lines[text].get_marker(), results.style(technique)[1])
            self.assertEqual(points[-1][0], 2000.0)
        # cssm2's two kernels: one colour and marker, two line styles.
        self.assertNotEqual(lines["cssm2 9x9"].get_linestyle(), lines["cssm2 3x3"].get_linestyle())
        self.assertIn("16.7 ms (60 Hz)", lines)
        matplotlib.pyplot.close(fig)
        # Two runs of one spec: a curve each, told apart by file.
        fig, info = charts.seed001_quads_figure(results.load([self.timing, self.both]))
        self.assertIn("cssm2 3x3 [both.json]", info["series"])
        self.assertIn("cssm2 3x3 [seed001.json]", info["series"])
        self.assertIn("composited-translucent", info["series"])
        matplotlib.pyplot.close(fig)

        fig, info = charts.seed001_fine_figure(results.load(self.composited))
        self.assertEqual(list(info["series"]), ["shadowmap", "translucent-shadows", "composited-translucent"])
        self.assertEqual([x for x, _ in info["draws"]["composited-translucent"][1]], [float(n) for n in range(31)])
        lines = {ln.get_label(): ln for ln in fig.axes[0].get_lines()}
        draws = lines["composited-translucent: translucent draws (inside the main pass)"]
        self.assertEqual(draws.get_linestyle(), "--")
        self.assertEqual(matplotlib.colors.to_hex(draws.get_color()), results.style("composited-translucent")[0])
        self.assertEqual(max(x for x, _ in info["series"]["shadowmap"][1]), 30.0)   # the fine spec's rows only
        matplotlib.pyplot.close(fig)


def stress_row(technique, case, value, threshold, fail=False, better=False, skipped=False):
    """A row of `shadowlab stress`'s results.json (the fields the chart reads)."""
    row = {"case": case, "technique": technique, "threshold": threshold, "skipped": skipped,
           "expected_to_fail": fail, "expected_to_pass": better}
    if not skipped:
        row.update({"value": value, "pass": value <= threshold})
        if fail or better:
            row["agrees_with_literature"] = fail != (value <= threshold)
    return row


class StripTool(unittest.TestCase):
    """tools/strip.py puts images side by side under their captions (seed 001's Figs. 5.3.2.B, 5.3.3.A)."""

    def test_strip_is_the_images_side_by_side_under_a_caption_band(self):
        import strip
        from PIL import Image
        with tempfile.TemporaryDirectory() as tmp:
            red, blue = os.path.join(tmp, "red.png"), os.path.join(tmp, "blue.png")
            Image.new("RGB", (40, 30), (255, 0, 0)).save(red)
            Image.new("RGB", (20, 50), (0, 0, 255)).save(blue)
            out = os.path.join(tmp, "strip.png")
            self.assertEqual(strip.main(["--out", out, red, "red", blue, "blue"]), 0)
            image = Image.open(out).convert("RGB")
            self.assertEqual(image.size, (60, 50 + 28))
            self.assertEqual(image.getpixel((10, 28 + 15)), (255, 0, 0))    # the first image, below the band
            self.assertEqual(image.getpixel((50, 28 + 40)), (0, 0, 255))    # the second, to its right
            self.assertEqual(image.getpixel((30, 28 + 40)), (24, 24, 24))   # below the shorter first image
            with contextlib.redirect_stderr(io.StringIO()), self.assertRaises(SystemExit) as odd:
                strip.main(["--out", out, red, "red", blue])                # a caption missing
            self.assertEqual(odd.exception.code, 2)
            with contextlib.redirect_stderr(io.StringIO()):
                self.assertEqual(strip.main(["--out", out, os.path.join(tmp, "missing.png"), "x"]), 2)


class StressChart(unittest.TestCase):
    """tools/stress_chart.py says, per cell, whether the verdict agrees with the case's claim."""

    def rows(self):
        return [
            stress_row("shadowmap", "shimmer-dolly", 0.0009, 0.0003, fail=True),        # fails, as claimed
            stress_row("shadowmap", "overlap", 0.0001, 0.0006),                       # no claim
            stress_row("vsm", "shimmer-dolly", 0.0001, 0.0003, fail=True),            # passes: claim: fails
            stress_row("vsm", "overlap", 0.0013, 0.0006, fail=True),                  # fails, as claimed
            stress_row("psm", "shimmer-dolly", 0.81, 0.02, better=True),              # fails: claim: passes
            stress_row("psm", "overlap", 0, 0, skipped=True),
            stress_row("lispsm", "shimmer-dolly", 0.0144, 0.02, better=True),         # passes, as claimed
            stress_row("lispsm", "overlap", 0.0002, 0.0006),
            stress_row("reference", "shimmer-dolly", 0.0, 0.0003),
            stress_row("reference", "overlap", 0.0, 0.0006),
        ]

    def test_marks_frames_and_count_follow_the_claim(self):
        fig, drawn, (agree, disagree) = stress_chart.draw(self.rows())
        expect = {
            ("shadowmap", "shimmer-dolly"): ("as claimed", True, stress_chart.FAIL, "solid"),
            ("shadowmap", "overlap"): ("", None, stress_chart.PASS, None),
            ("vsm", "shimmer-dolly"): ("claim: fails", False, stress_chart.PASS, "solid"),
            ("vsm", "overlap"): ("as claimed", True, stress_chart.FAIL, "solid"),
            ("psm", "shimmer-dolly"): ("claim: passes", False, stress_chart.FAIL, "dashed"),
            ("psm", "overlap"): ("", None, stress_chart.SKIPPED, None),
            ("lispsm", "shimmer-dolly"): ("as claimed", True, stress_chart.PASS, "dashed"),
            ("reference", "shimmer-dolly"): ("as claimed", True, stress_chart.PASS, None),
        }
        for key, (mark, agrees, colour, style) in expect.items():
            cell = drawn[key]
            self.assertEqual(cell["mark"], mark, key)
            self.assertEqual(cell["agrees"], agrees, key)
            self.assertEqual(cell["colour"], colour, key)
            if style is None:
                self.assertIsNone(cell["frame"], key)
            else:
                self.assertEqual(cell["frame"]["style"], style, key)
                self.assertEqual(cell["frame"]["colour"], stress_chart.AGREES if agrees else stress_chart.DISAGREES, key)
            if mark:
                self.assertIn(mark, cell["text"], key)
        # The reference is not counted: 3 named cells agree (shadowmap, vsm overlap, lispsm), 2 do not.
        self.assertEqual((agree, disagree), (3, 2))
        texts = [t.get_text() for t in fig.axes[0].texts]
        self.assertEqual(sum("claim: fails" in t for t in texts), 1)
        self.assertEqual(sum("claim: passes" in t for t in texts), 1)
        self.assertIn("3 of 5 cells the claims name agree", fig.axes[0].get_title())
        stress_chart.plt.close(fig)

    def test_png_written_and_agreement_matches_the_committed_run(self):
        with tempfile.TemporaryDirectory(prefix="shadowlab-stress-chart-") as out:
            path = os.path.join(out, "results.json")
            with open(path, "w") as f:
                json.dump(self.rows(), f)
            rc, printed = call(stress_chart, path, "--out", out, "--dpi", "40")
            self.assertEqual(rc, 0)
            with open(printed.strip(), "rb") as f:
                self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")
        # On the committed GPU run (rows written before agrees_with_literature existed), the chart
        # agrees where the suite's rule (stress.cpp: expected_to_fail != pass) says so.
        committed = os.path.join(ROOT, "docs", "results", "h200-2026-12-02-seed002", "stress", "results.json")
        with open(committed) as f:
            rows = json.load(f)
        named = [r for r in rows if not r.get("skipped") and (r.get("expected_to_fail") or r.get("expected_to_pass"))]
        self.assertGreater(len(named), 5)
        for row in named:
            rule = row.get("agrees_with_literature", bool(row.get("expected_to_fail")) != bool(row["pass"]))
            self.assertEqual(stress_chart.claim_mark(row)[1], rule, (row["technique"], row["case"]))
        fig, _, (agree, disagree) = stress_chart.draw(rows)
        self.assertEqual(agree + disagree, len(named))
        self.assertEqual(disagree, sum(1 for r in named if bool(r.get("expected_to_fail")) == bool(r["pass"])))
        stress_chart.plt.close(fig)


if __name__ == "__main__":
    unittest.main()
