#!/usr/bin/python3
"""Seed 002 Figs. 8.7 and 9.3: perspective aliasing against view depth, measured beside analytic.

    shadowlab eval --scene aliasing-plane --size 64x2048 --technique lispsm --json > lispsm.json
    aliasing_curves.py --out fig8.7.png --eye-height 0.5 uniform.json psm.json lispsm.json

Each input is the JSON of `shadowlab eval --json`; its texel_footprint.byViewDepth holds, per
view-depth bin, the median of the host's depthError: pixels per shadow-map texel along the
direction the receiver recedes from the viewer, with eq. 6.1's projection term divided out, i.e.
eq. 8.1's dp/ds as eq. 8.2-8.9 take it. Every input is drawn as measured points, and beside it, in
the same colour, the analytic curve of its parameterisation in the same units (pixels per texel),
for a map of R texels (the input's resolution) on a screen H pixels high (its height), field of
view --fov:

  shadowmap (uniform, eq. 8.2)  dp/ds = F d / (R z)
  psm (eq. 8.3)                 dp/ds = F z (1/z_n - 1/z_f) / R    (s linear in 1/z over [z_n, z_f])
  lispsm (eq. 8.9)              dp/ds = F (z - z_n + n)^2 d / (R n (n + d) z),  n = z_n + sqrt(z_n z_v)
  tsm                           measured only: seed 002 gives no curve for trapezoidal shadow maps
  --logarithmic (eq. 8.4)       dp/ds = F ln(z_f / z_n) / R, the ideal parameterisation s = ln(z / z_n) /
                                ln(z_f / z_n) (constant: every depth gets the same error), drawn
                                dashed for the first input's R and H

with F = (H / 2) / tan(fov / 2), d = z_f - z_n, z_v lispsm's virtual far plane (sec. 9.2.5) or z_f.
--eye-height h multiplies each by sqrt(1 + h^2 / z^2), the ground plane's own factor (a ground step
seen at elevation atan(h / z) spans 1 / cos of it more screen than the seed's idealised edge).
The seed's curves assume the optimal case (view across the light, frustum inside the scene):
`aliasing-plane` is that case. psm's measured curve departs from eq. 8.3 where its near plane and
crop differ from the idealised s = 1/z map; the analytic line is the seed's.

Only bins with at least --min-pixels pixels are drawn. Needs python3-matplotlib.
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

KINDS = {"shadowmap": "uniform", "psm": "PSM", "lispsm": "LiSPSM", "tsm": "TSM"}
EQUATIONS = {"shadowmap": "8.2", "psm": "8.3", "lispsm": "8.9"}


def parameters(text):
    """'a=1 b=x' -> {'a': '1', 'b': 'x'}"""
    out = {}
    for item in text.split():
        key, _, value = item.partition("=")
        out[key] = value
    return out


def analytic(technique, z, zn, zf, virtual_far, resolution, focal, eye_height):
    """Eq. 8.2, 8.3 or 8.9 in pixels per texel at view depth z (see the module's text)."""
    d = zf - zn
    if technique == "shadowmap":
        value = d / z
    elif technique == "psm":
        value = z * (1.0 / zn - 1.0 / zf)
    elif technique == "lispsm":
        zv = virtual_far if 0.0 < virtual_far < zf else zf
        n = zn + math.sqrt(zn * zv)
        value = (z - zn + n) ** 2 * d / (n * (n + d) * z)
    elif technique == "logarithmic":
        value = math.log(zf / zn)
    else:
        raise ValueError(f"no analytic curve for technique '{technique}' (expected one of: {', '.join(KINDS)})")
    return focal * value / resolution * math.sqrt(1.0 + (eye_height / z) ** 2)


def load(path):
    try:
        with open(path, encoding="utf-8") as f:
            data = json.load(f)
    except (OSError, ValueError) as e:
        raise ValueError(f"{path}: {e}") from e
    bins = data.get("texel_footprint", {}).get("byViewDepth")
    if not isinstance(bins, list) or not bins:
        raise ValueError(f"{path}: no texel_footprint.byViewDepth (the JSON of `shadowlab eval --json` of a technique "
                         "that reports its shadow maps, from a build that bins m by view depth)")
    for key in ("technique", "parameters", "height"):
        if key not in data:
            raise ValueError(f"{path}: no '{key}' field (not the output of `shadowlab eval --json`?)")
    return data


def label_of(data):
    params = parameters(data["parameters"])
    technique = data["technique"]
    text = KINDS.get(technique, technique)
    if technique == "lispsm":
        vf = float(params.get("virtual_far", "0") or 0)
        text += f" (z_f {vf:g} for n)" if vf > 0 else " (n_opt)"
    if technique == "shadowmap" and "fit" in params:
        text += f", fit {params['fit']}"
    return text


def figure(inputs, args):
    fig, ax = plt.subplots(figsize=(7.5, 4.8))
    colours = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2"]
    focal_of = lambda height: 0.5 * height / math.tan(math.radians(args.fov) / 2.0)
    for index, data in enumerate(inputs):
        params = parameters(data["parameters"])
        technique = data["technique"]
        resolution = float(params.get("resolution", 0) or 0)
        if resolution <= 0:
            raise ValueError(f"{technique}: no resolution in its parameters '{data['parameters']}'")
        colour = results.STYLE.get(technique, (colours[index % len(colours)],))[0] if len(inputs) <= 3 \
            else colours[index % len(colours)]
        points = [(b["depth"], b["depthError"]) for b in data["texel_footprint"]["byViewDepth"]
                  if b["pixels"] >= args.min_pixels and b["depthError"] > 0]
        label = label_of(data)
        ax.plot([p[0] for p in points], [p[1] for p in points], "o", ms=3.5, color=colour, label=f"{label}, measured")
        zs = [args.near + (args.far - args.near) * i / 400.0 for i in range(401)]
        if technique in EQUATIONS:
            curve = [analytic(technique, z, args.near, args.far, float(params.get("virtual_far", "0") or 0), resolution,
                              focal_of(float(data["height"])), args.eye_height) for z in zs]
            ax.plot(zs, curve, "-", lw=1.2, color=colour, alpha=0.8, label=f"{label}, eq. {EQUATIONS[technique]}")
        elif technique not in KINDS:
            raise ValueError(f"no analytic curve for technique '{technique}' (expected one of: {', '.join(KINDS)})")
        if args.logarithmic and index == 0:
            curve = [analytic("logarithmic", z, args.near, args.far, 0.0, resolution, focal_of(float(data["height"])),
                              args.eye_height) for z in zs]
            ax.plot(zs, curve, "--", lw=1.2, color="#555555", label="logarithmic (ideal), eq. 8.4")
    ax.set_yscale("log")
    ax.set_xlim(0, args.far)
    ax.set_xlabel("view depth z")
    ax.set_ylabel("dp/ds: pixels per texel along depth")
    ax.set_title(args.title)
    ax.grid(True, which="both", alpha=0.25)
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    fig.savefig(args.out, dpi=args.dpi)
    plt.close(fig)


def parse_args(argv):
    parser = argparse.ArgumentParser(prog="aliasing_curves.py", description=__doc__.split("\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter,
                                     epilog="\n".join(__doc__.split("\n")[2:]))
    parser.add_argument("inputs", nargs="+", metavar="EVAL_JSON", help="outputs of `shadowlab eval --json`")
    parser.add_argument("--out", required=True, metavar="PNG", help="the figure to write")
    parser.add_argument("--near", type=float, default=1.0, help="the camera's near plane z_n (default 1)")
    parser.add_argument("--far", type=float, default=100.0, help="the camera's far plane z_f (default 100)")
    parser.add_argument("--fov", type=float, default=60.0, help="vertical field of view in degrees (default 60)")
    parser.add_argument("--eye-height", type=float, default=0.0,
                        help="the camera's height over the ground, for the ground's 1/cos e factor (default 0: the seed's idealisation)")
    parser.add_argument("--logarithmic", action="store_true",
                        help="also draw eq. 8.4's ideal logarithmic parameterisation (for the first input's map and screen)")
    parser.add_argument("--min-pixels", type=int, default=64, help="bins with fewer pixels are not drawn (default 64)")
    parser.add_argument("--title", default="perspective aliasing against view depth", help="the figure's title")
    parser.add_argument("--dpi", type=int, default=120)
    args = parser.parse_args(argv)
    if not 0.0 < args.near < args.far:
        parser.error(f"--near {args.near} and --far {args.far}: need 0 < near < far")
    return args


def main(argv=None):
    args = parse_args(sys.argv[1:] if argv is None else argv)
    try:
        figure([load(path) for path in args.inputs], args)
    except ValueError as e:
        print(f"aliasing_curves.py: {e}", file=sys.stderr)
        return 2
    print(args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
