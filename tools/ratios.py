#!/usr/bin/python3
"""The ratios the project reports from one GPU run (issues 5 and 6), as Markdown.

    python3 tools/ratios.py default.json seed000.json

default.json: `shadowlab bench --spec assets/bench/default.json`; seed000.json: the same with
assets/bench/seed000.json. Every ratio compares rows of the same run on the same machine.
"""
import json
import statistics
import sys


def rows_where(rows, **match):
    out = []
    for row in rows:
        if all(str(row.get(k)) == str(v) for k, v in match.items()):
            out.append(row)
    return out


def one(rows, **match):
    found = rows_where(rows, **match)
    return found[0] if found else None


def main(default_path, seed_path):
    d = json.load(open(default_path))
    s = json.load(open(seed_path))
    print(f"GPU {d[0]['gpu']}, driver {d[0]['driver']}, {d[0]['date']}, build {d[0]['commit']}\n")

    print("## Shadow pass against the depth-only floor (same geometry, resolution and light)\n")
    print("| scene | resolution | depth floor ms | shadowmap shadow pass ms | ratio |\n|---|---:|---:|---:|---:|")
    for scene in ("cube", "forest"):
        for res in (256, 512, 1024, 2048, 4096, 8192):
            floor = one(d, scene=scene, technique="depth-floor", **{"param.resolution": res})
            sm = [r for r in rows_where(d, scene=scene, technique="shadowmap", **{"param.resolution": res})
                  if r.get("width") == 1920 and "gpu_shadow_map_ms" in r]
            if floor and sm:
                a, b = floor["gpu_depth_floor_ms"], sm[0]["gpu_shadow_map_ms"]
                print(f"| {scene} | {res} | {a:.3f} | {b:.3f} | {b / a:.2f}x |")

    print("\n## Frame-time overhead of shadowmap (2048) over none, 1920x1080\n")
    print("| scene | none ms | shadowmap ms | overhead |\n|---|---:|---:|---:|")
    for scene in ("cube", "spheres", "contact", "overlap", "pillars", "forest"):
        none = [r for r in rows_where(d, scene=scene, technique="none") if r.get("width") == 1920]
        sm = [r for r in rows_where(d, scene=scene, technique="shadowmap", **{"param.resolution": 2048}) if r.get("width") == 1920]
        if none and sm:
            a, b = none[0]["gpu_frame_ms"], sm[0]["gpu_frame_ms"]
            print(f"| {scene} | {a:.3f} | {b:.3f} | +{b - a:.3f} ms ({100 * (b / a - 1):.0f}%) |")

    print("\n## Host CPU time per frame (median of medians, submission included, waits for the GPU excluded)\n")
    print("| scene | techniques | median ms | max ms |\n|---|---:|---:|---:|")
    for scene in ("cube", "spheres", "contact", "overlap", "pillars", "forest", "dense"):
        values = [r["cpu_frame_ms"] for r in d if r.get("scene") == scene and r.get("technique") not in ("depth-floor",)
                  and "cpu_frame_ms" in r]
        if values:
            print(f"| {scene} | {len(values)} rows | {statistics.median(values):.3f} | {max(values):.3f} |")

    print("\n## Time against triangle count (dense, 400 spheres, 1920x1080)\n")
    print("| triangles | none frame ms | shadowmap frame ms | shadow pass ms | depth floor ms |\n|---:|---:|---:|---:|---:|")
    for seg in (8, 16, 32, 64, 128, 174):
        none = one(d, scene="dense", technique="none", **{"scene.segments": float(seg)})
        sm = one(d, scene="dense", technique="shadowmap", **{"scene.segments": float(seg)})
        fl = one(d, scene="dense", technique="depth-floor", **{"scene.segments": float(seg)})
        if none and sm:
            print(f"| {none['triangles']:,} | {none['gpu_frame_ms']:.3f} | {sm['gpu_frame_ms']:.3f} | "
                  f"{sm.get('gpu_shadow_map_ms', 0):.3f} | {fl['gpu_depth_floor_ms'] if fl else float('nan'):.3f} |")

    print("\n## Adaptive PCF against PCF (same kernel footprint, 1024 map), seed 000: +15-104% FPS (smallest kernel), +392-1473% (largest)\n")
    print("| scene | size | n | PCF ms | adaptive ms | FPS gain | PCF soft MAE | adaptive soft MAE | early-out rate |\n|---|---|---:|---:|---:|---:|---:|---:|---:|")
    for scene in ("cube", "dragon-like"):
        for w, h in ((1280, 720), (1920, 1080), (2560, 1440)):
            for n in (3, 7, 11, 15):
                p = one(s, spec="pcf-kernel", scene=scene, width=w, **{"param.kernel": n})
                a = one(s, spec="adaptive-kernel", scene=scene, width=w, **{"param.grid": n})
                if p and a:
                    gain = 100 * (p["gpu_frame_ms"] / a["gpu_frame_ms"] - 1)
                    print(f"| {scene} | {w}x{h} | {n} | {p['gpu_frame_ms']:.3f} | {a['gpu_frame_ms']:.3f} | {gain:+.0f}% | "
                          f"{p['soft_mae']:.4f} | {a['soft_mae']:.4f} | {a.get('stat.early_out_rate', float('nan')):.2f} |")

    print("\n## VSM with twice the kernel (2n+1 blur) against PCF n x n, 1024 map\n")
    print("| scene | size | n | PCF ms | VSM ms | VSM/PCF | PCF soft MAE | VSM soft MAE |\n|---|---|---:|---:|---:|---:|---:|---:|")
    for scene in ("cube", "dragon-like"):
        for w, h in ((1280, 720), (1920, 1080), (2560, 1440)):
            for n in (1, 3, 5, 7, 9, 11, 13, 15):
                p = one(s, spec="pcf-kernel", scene=scene, width=w, **{"param.kernel": n})
                v = one(s, spec="vsm-kernel", scene=scene, width=w, **{"param.kernel": 2 * n + 1})
                if p and v:
                    print(f"| {scene} | {w}x{h} | {n} | {p['gpu_frame_ms']:.3f} | {v['gpu_frame_ms']:.3f} | "
                          f"{v['gpu_frame_ms'] / p['gpu_frame_ms']:.2f} | {p['soft_mae']:.4f} | {v['soft_mae']:.4f} |")

    print("\n## Every technique at 1024 map, 1920x1080, 11x11 kernels (seed 000 Fig. 4.15)\n")
    print("| scene | technique | frame ms | technique passes ms | MiB | hard MAE | soft MAE |\n|---|---|---:|---:|---:|---:|---:|")
    for scene in ("cube", "dragon-like", "contact", "dense"):
        for r in rows_where(s, spec="fig415", scene=scene):
            print(f"| {scene} | {r['technique']} | {r['gpu_frame_ms']:.3f} | {r['gpu_technique_ms']:.3f} | "
                  f"{r['gpu_bytes'] / 1048576:.1f} | {r.get('hard_mae', float('nan')):.4f} | {r.get('soft_mae', float('nan')):.4f} |")
    print("\nPCSS against adaptive PCF (seed 000: about 2x):\n")
    for scene in ("cube", "dragon-like", "contact", "dense"):
        p = one(s, spec="fig415", scene=scene, technique="pcss")
        a = one(s, spec="fig415", scene=scene, technique="adaptive-pcf")
        if p and a:
            print(f"- {scene}: frame {p['gpu_frame_ms'] / a['gpu_frame_ms']:.2f}x, technique passes "
                  f"{p['gpu_technique_ms'] / max(a['gpu_technique_ms'], 1e-9):.2f}x")

    print("\n## PCSS against light size (1024 map)\n")
    print("| scene | size | light size (deg) | frame ms | soft MAE | penumbra share |\n|---|---|---:|---:|---:|---:|")
    for r in rows_where(s, spec="pcss-light"):
        print(f"| {r['scene']} | {r['width']}x{r['height']} | {r['light_size']:.2f} | {r['gpu_frame_ms']:.3f} | "
              f"{r['soft_mae']:.4f} | {r.get('technique_penumbra_fraction', 0):.4f} |")
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 3:
        print(__doc__)
        sys.exit(2)
    sys.exit(main(sys.argv[1], sys.argv[2]))
