#!/usr/bin/env bash
# Bad input gets a clear message naming the file or value and exit code 2; the app never crashes.
set -uo pipefail
shadowlab=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0

expect() {   # expect CODE PATTERN -- ARGS...
    local code=$1 pattern=$2
    shift 3
    local output
    output=$("$shadowlab" "$@" 2>&1)
    local actual=$?
    if [ "$actual" != "$code" ] || ! grep -q -- "$pattern" <<<"$output"; then
        echo "FAIL: shadowlab $* -> exit $actual (want $code), output:"
        echo "$output" | sed 's/^/    /'
        failures=$((failures + 1))
    else
        echo "ok: shadowlab $* -> $code, '$pattern'"
    fi
}

echo '{"name": "broken", "objects": [' > "$tmp/broken.json"
echo '{"objects": [{"shape": "cone"}]}' > "$tmp/cone.json"
expect 2 "broken.json" -- render --backend osmesa --scene "$tmp/broken.json" --out "$tmp/a.png"
expect 2 "cone" -- render --backend osmesa --scene "$tmp/cone.json" --out "$tmp/a.png"
printf 'not a png' > "$tmp/fake.png"
echo '{"materials": {"w": {"alpha": 0.5, "transmissionTexture": "fake.png"}}, "objects": [{"shape": "plane", "material": "w"}]}' > "$tmp/texture.json"
expect 2 "transmissionTexture: .*fake.png: not a readable PNG" -- render --backend osmesa --scene "$tmp/texture.json" --out "$tmp/a.png"
expect 2 "no-such-scene" -- render --backend osmesa --scene no-such-scene --out "$tmp/a.png"
expect 2 "out of range" -- render --backend osmesa -t shadowmap --set resolution=10 --out "$tmp/a.png"
expect 2 "has no parameter 'kernel'" -- render --backend osmesa -t shadowmap --set kernel=3 --out "$tmp/a.png"
# The host's parameters (the eye-space blur, seed 002 sec. 6.3) are checked like a technique's.
expect 2 "parameter 'shadow_blur': 99 is out of range" -- render --backend osmesa -t shadowmap --set host.shadow_blur=99 --out "$tmp/a.png"
expect 2 "'flat' is not one of phong, none" -- render --backend osmesa -t shadowmap --set host.lighting=flat --out "$tmp/a.png"
expect 2 "host.shadow_blur=...: parameter 'shadow_blur': 40 is out of range" -- bench --backend osmesa --techniques shadowmap --sweep host.shadow_blur=0,40 --out "$tmp/b.json"
expect 2 "no such technique" -- render --backend osmesa -t nonexistent --out "$tmp/a.png"
expect 2 "expected glfw, egl or osmesa" -- render --backend vulkan --out "$tmp/a.png"
expect 2 "WIDTHxHEIGHT" -- render --backend osmesa --size 12by3 --out "$tmp/a.png"
expect 2 "no debug image 'nope'" -- render --backend osmesa -t shadowmap --view nope --out "$tmp/a.png"
expect 0 "wrote" -- render --backend osmesa -t shadowmap --view "shadow map" --size 64x48 --out "$tmp/map.png"
[ -s "$tmp/map.png" ] || { echo "FAIL: no PNG written"; failures=$((failures + 1)); }
expect 0 '"id": "shadowmap"' -- list --json

# --- issue 12: camera and light paths, `bench --path`, `render --path`, `stress`.
printf '{"keyframes": [{"time": 1}, {"time": 0.5}]}' > "$tmp/backwards.json"
printf '{"keyframes": [{"time": 0, "camera": {"posiiton": [0, 1, 2]}}]}' > "$tmp/typo.json"
printf '{"keyframes": [{"time": 0, "light": {"position": [0, 5, 0]}}]}' > "$tmp/positioned.json"
printf '{"keyframes": [' > "$tmp/truncated.json"
pathrender=(render --backend osmesa --size 48x32 -t shadowmap)
expect 2 "backwards.json: keyframes\[1\].time: times must increase" -- "${pathrender[@]}" --path "$tmp/backwards.json" --out "$tmp/frames"
expect 2 "typo.json: keyframes\[0\].camera.posiiton: unknown field" -- "${pathrender[@]}" --path "$tmp/typo.json" --out "$tmp/frames"
expect 2 "positioned.json: moves the light by position, but scene 'cube' has a directional light" -- "${pathrender[@]}" --path "$tmp/positioned.json" --out "$tmp/frames"
expect 2 "truncated.json" -- "${pathrender[@]}" --path "$tmp/truncated.json" --out "$tmp/frames"
expect 2 "no-such-path.json" -- "${pathrender[@]}" --path "$tmp/no-such-path.json" --out "$tmp/frames"
expect 2 "not a file, nor a path of scene 'cube' or a built-in path (orbit, dolly" -- "${pathrender[@]}" --path spiral --out "$tmp/frames"
expect 2 "backwards.json" -- bench --backend osmesa --size 48x32 --techniques shadowmap --path "$tmp/backwards.json" --out "$tmp/p.json"
expect 2 "--path: times one setting per technique" -- bench --backend osmesa --techniques shadowmap --path orbit --sweep resolution=512,1024 --out "$tmp/p.json"
expect 0 "wrote 3 frames of path 'dolly'" -- "${pathrender[@]}" --path dolly --path-frames 3 --out "$tmp/frames"
[ "$(ls "$tmp/frames" | grep -c '^frame_0000[0-2].png$')" = 3 ] || { echo "FAIL: render --path did not write frame_00000..2.png"; failures=$((failures + 1)); }
expect 0 "p50" -- bench --backend osmesa --size 48x32 --techniques shadowmap,pcf --path sweep --path-frames 6 --warmup 2 --accuracy --out "$tmp/path.json"
python3 - "$tmp/path.json" <<'PY' || { echo "FAIL: bench --path results"; failures=$((failures + 1)); }
import json, sys
rows = json.load(open(sys.argv[1]))
assert [r["technique"] for r in rows] == ["shadowmap", "pcf"], rows
for r in rows:
    assert len(r["frame_ms_per_frame"]) == 6 and r["frame_ms_p5"] <= r["frame_ms_p50"] <= r["frame_ms_p95"] <= r["frame_ms_max"], r
    assert len(r["flicker_per_frame"]) == 6 and r["flicker_mean"] >= 0 and r["popping"] >= 0, r
print("ok: bench --path rows: per-frame times, percentiles, temporal metrics")
PY
printf '{"cases": [{"id": "x", "title": "t", "scene": "cube", "metric": "flicker", "threshold": 0.1, "claim": "c", "source": "s"}]}' > "$tmp/cases.json"
expect 2 "cases.json: cases\[0\].metric: a temporal metric needs a path" -- stress --backend osmesa --cases-file "$tmp/cases.json" --out "$tmp/stress"
expect 2 "--techniques: no technique 'nonesuch'" -- stress --backend osmesa --techniques nonesuch --out "$tmp/stress"
expect 2 "--cases: no case 'nonesuch'" -- stress --backend osmesa --techniques shadowmap --cases nonesuch --out "$tmp/stress"
expect 2 "--translucent-layers: Value 9 not in range 0 to 8" -- eval --backend osmesa --scene layered-quads --translucent-layers 9
expect 2 "--translucent-layers: Value -1 not in range 0 to 8" -- eval --backend osmesa --scene layered-quads --translucent-layers -1
expect 0 "stress: 2 cells" -- stress --backend osmesa --techniques shadowmap,reference --cases acne-5 --out "$tmp/stress"
for file in README.md results.json results.csv stress.png images/shadowmap-acne-5.png; do
    [ -s "$tmp/stress/$file" ] || { echo "FAIL: stress did not write $file"; failures=$((failures + 1)); }
done

# --- issue 13: every bad input is a clear error (exit 2 naming the file or option), never a
# crash, a hang or an exhausted machine. Each run is bounded by `timeout`, so a hang fails.
build=$(dirname "$shadowlab")
expect_bounded() {   # like expect, but a run over ${bound:-60} s is a failure (exit 124)
    local code=$1 pattern=$2
    shift 3
    local output actual
    output=$(timeout "${bound:-60}" "$shadowlab" "$@" 2>&1)
    actual=$?
    if [ "$actual" != "$code" ] || ! grep -q -- "$pattern" <<<"$output"; then
        echo "FAIL: shadowlab $* -> exit $actual (want $code), output:"
        echo "$output" | sed 's/^/    /'
        failures=$((failures + 1))
    else
        echo "ok: shadowlab $* -> $code, '$pattern'"
    fi
}
render=(render --backend osmesa --size 64x48 --frames 1 --out "$tmp/a.png")

# JSON numbers, floats as stored, non-finite light
echo '{"objects": [{"shape": "box", "size": [1e400, 1, 1]}]}' > "$tmp/e400.json"
expect_bounded 2 "e400.json: JSON error: number overflow parsing '1e400'" -- "${render[@]}" --scene "$tmp/e400.json"
echo '{"objects": [{"shape": "box", "size": [1e300, 1, 1]}]}' > "$tmp/e300.json"
expect_bounded 2 "e300.json: objects\[0\].size\[0\]: too large for single precision" -- "${render[@]}" --scene "$tmp/e300.json"
echo '{"objects": [{"shape": "sphere", "radius": 1e-300}]}' > "$tmp/em300.json"
expect_bounded 2 "em300.json: objects\[0\].radius: too small" -- "${render[@]}" --scene "$tmp/em300.json"
echo '{"light": {"type": "point", "position": [0, 1e300, 0], "size": 0.5}, "objects": [{"shape": "box"}]}' > "$tmp/inflight.json"
expect_bounded 2 "light.position\[1\]: too large" -- eval --backend osmesa --size 64x48 --frames 1 --scene "$tmp/inflight.json"
echo '{"light": {"type": "point", "position": [0, 5, 0], "size": 1e300}, "objects": [{"shape": "box"}]}' > "$tmp/infsize.json"
expect_bounded 2 "light.size: too large" -- "${render[@]}" --view reference --scene "$tmp/infsize.json"
expect_bounded 2 "\[json.exception\|number overflow" -- bench --backend osmesa --spec "$tmp/e400.json" --out "$tmp/b.csv"

# Files that are not regular: a FIFO would block forever, /dev/zero never ends
mkfifo "$tmp/fifo.json" "$tmp/fifo.obj" "$tmp/fifo.mtl"
expect_bounded 2 "fifo.json: cannot read scene file: a FIFO, not a regular file" -- "${render[@]}" --scene "$tmp/fifo.json"
expect_bounded 2 "/dev/zero: cannot read scene file: a character device" -- "${render[@]}" --scene /dev/zero
expect_bounded 2 "fifo.json: cannot read benchmark spec: a FIFO" -- bench --backend osmesa --spec "$tmp/fifo.json" --out "$tmp/b.csv"
echo '{"objects": [{"shape": "obj", "file": "fifo.obj"}]}' > "$tmp/fifo-obj.json"
expect_bounded 2 "objects\[0\].file: .*fifo.obj: cannot read OBJ file: a FIFO" -- "${render[@]}" --scene "$tmp/fifo-obj.json"

# OBJ: material libraries are never opened; indices are checked in 64 bits
printf 'mtllib /dev/zero\nmtllib fifo.mtl\nv 0 0 0\nv 1 0 0\nv 0 0 -1\nf 1 2 3\n' > "$tmp/mtl.obj"
echo '{"objects": [{"shape": "plane"}, {"shape": "obj", "file": "mtl.obj"}]}' > "$tmp/mtl.json"
expect_bounded 0 "wrote" -- "${render[@]}" --scene "$tmp/mtl.json"
printf 'v 0 0 0\nv 1 0 0\nv 0 0 -1\nf 1 2 4294967297\n' > "$tmp/wrap.obj"
echo '{"objects": [{"shape": "obj", "file": "wrap.obj"}]}' > "$tmp/wrap.json"
expect_bounded 2 "wrap.obj:4: face refers to vertex 4294967297 (index out of range)" -- "${render[@]}" --scene "$tmp/wrap.json"

# The budget: totals over every block, checked before anything is generated; --budget changes it
{ printf '{"objects": ['; for i in $(seq 30); do [ "$i" = 1 ] || printf ','; printf '{"shape": "box", "repeat": {"count": 1000000}}'; done; echo ']}'; } > "$tmp/many.json"
# The first block's million instances are checked one by one (transforms in range) before the
# second block goes over the budget: 0.3 s in Release, about 30 s of CPU under ASan at -O0, more
# when ctest runs tests beside it. The bound catches a hang or an allocation, not the speed.
bound=300 expect_bounded 2 "objects\[1\].repeat: the scene would have 2000000 objects, more than the budget of 1000000" -- "${render[@]}" --scene "$tmp/many.json"
echo '{"objects": [{"shape": "sphere", "segments": 4096, "rings": 4096}, {"shape": "sphere", "segments": 4096, "rings": 4095}, {"shape": "sphere", "segments": 4096, "rings": 4094}]}' > "$tmp/spheres.json"
expect_bounded 2 "objects\[1\]: the scene would draw .* triangles per frame, more than the budget" -- "${render[@]}" --scene "$tmp/spheres.json"
expect_bounded 2 "more than the budget of 10; raise it with --budget objects=N" -- "${render[@]}" --scene spheres --budget objects=10
expect_bounded 0 "wrote" -- "${render[@]}" --scene spheres --budget objects=100,gpu-mib=512
expect_bounded 2 "--budget 'objects=lots'" -- "${render[@]}" --budget objects=lots
expect_bounded 2 "render targets .* would need more than the GPU memory budget" -- render --backend osmesa --size 16384x16384 --out "$tmp/a.png"

# bench: the whole command checked before the first frame
bench=(bench --backend osmesa --size 64x48 --frames 1 --warmup 0 --out "$tmp/b.csv")
expect_bounded 2 "--sweep light.size=...: 'abc' is not a number" -- "${bench[@]}" --sweep light.size=abc
expect_bounded 2 "--sweep resolution=...: shadowmap: parameter 'resolution': 'abc' is not a number" -- "${bench[@]}" -t shadowmap --techniques shadowmap --sweep resolution=256,abc --depth-floor
expect_bounded 2 "--reference 'sofft': expected hard, soft, both or auto" -- "${bench[@]}" --accuracy --reference sofft
expect_bounded 2 "--reference 'bogus'" -- "${bench[@]}" --accuracy --reference bogus
expect_bounded 2 "--samples 0: expected 1 to 4096" -- "${bench[@]}" --accuracy --samples 0
expect_bounded 2 "--reference-adaptive 'maybe': expected on or off" -- "${bench[@]}" --accuracy --reference-adaptive maybe
expect_bounded 2 "--reference-adaptive 'yes': expected on or off" -- eval --backend osmesa --size 64x48 --frames 1 --reference-adaptive yes
expect_bounded 2 "--size '64x64junk': expected WIDTHxHEIGHT" -- "${bench[@]}" --size 64x64junk
expect_bounded 2 "--scenes 'nowhere': nowhere: cannot open scene file" -- "${bench[@]}" --scenes cube,contact,nowhere
expect_bounded 2 "--techniques: no technique 'pfc'" -- "${bench[@]}" --techniques shadowmap,pfc
expect_bounded 2 "--sweep scene.floating=...: '1x' is not a number" -- "${bench[@]}" --scenes spheres --sweep scene.floating=4,1x
expect_bounded 2 "--sweep light.size=...: '60' on scene 'cube'" -- "${bench[@]}" --sweep light.size=1,60
rm -f "$tmp/b.csv"
expect_bounded 2 "--scenes 'nowhere'" -- "${bench[@]}" --techniques none --scenes cube,nowhere
[ ! -e "$tmp/b.csv" ] || { echo "FAIL: a row was measured before the bad scene was found"; failures=$((failures + 1)); }

# --light-size: one range with scene files (0 to 45 degrees for directional lights)
for size in -1 nan -inf inf abc; do
    expect_bounded 2 "--light-size '$size': expected a finite number >= 0" -- "${render[@]}" --light-size="$size"
done
expect_bounded 2 "--light-size 1000: a directional light's size is its angular radius in degrees, 0 to 45" -- "${render[@]}" --light-size 1000
expect_bounded 0 "wrote" -- "${render[@]}" --light-size 2
expect_bounded 2 "--light-size on scene 'cube'" -- "${bench[@]}" --techniques none --light-size 1000
expect_bounded 2 "--light-dir '1e39,0,0'" -- "${render[@]}" --light-dir 1e39,0,0

# What the device supports (llvmpipe: 4 samples); write errors
expect_bounded 2 "--msaa 8: this device supports MSAA up to" -- "${render[@]}" --msaa 8
expect_bounded 1 "/dev/full: write failed (No space left on device)" -- render --backend osmesa --size 64x48 --frames 1 --out /dev/full
expect_bounded 1 "/dev/full: write failed" -- bench --backend osmesa --size 64x48 --frames 1 --warmup 0 --techniques none --out /dev/full
output=$("$shadowlab" list --json 2>&1 >/dev/full); code=$?
if [ "$code" = 1 ] && grep -q "standard output: write failed" <<<"$output"; then echo "ok: list --json > /dev/full -> 1"
else echo "FAIL: list --json > /dev/full -> exit $code: $output"; failures=$((failures + 1)); fi

# Broken plugins: list never crashes and names each file; duplicate ids name both; create() null
mkdir -p "$tmp/plugins"
cp "$build"/test_plugins/bad_*.so "$build"/test_plugins/reload_v1.so "$tmp/plugins/"
export SHADOWLAB_PLUGIN_DIR="$tmp/plugins"
expect_bounded 0 "bad_huge_param_count.so: invalid descriptor: paramCount 100000000 is more than 256" -- list
expect_bounded 0 "claimed by 2 libraries: .*bad_duplicate_a.so, .*bad_duplicate_b.so" -- list --json
expect_bounded 1 "bad_create_null.so: create() returned nothing" -- "${render[@]}" -t create_null
unset SHADOWLAB_PLUGIN_DIR

# The scratch folder: gone after a run, after SIGINT and SIGTERM; stale ones of dead processes cleaned
mkdir -p "$tmp/t/shadowlab-999999999" && touch "$tmp/t/shadowlab-999999999/old.so" && touch -d '-1 hour' "$tmp/t/shadowlab-999999999"
TMPDIR="$tmp/t" "$shadowlab" list >/dev/null 2>&1
left=$(ls "$tmp/t")
if [ -z "$left" ]; then echo "ok: no scratch folder left after list, the stale one removed"
else echo "FAIL: left in TMPDIR after list: $left"; failures=$((failures + 1)); fi
for signal in INT TERM; do
    mkdir -p "$tmp/s$signal"
    result=$(TMPDIR="$tmp/s$signal" python3 - "$shadowlab" "$tmp/s$signal" "$signal" <<'PY'
import glob, os, signal, subprocess, sys, time
shadowlab, tmp, name = sys.argv[1:4]
signal.signal(signal.SIGINT, signal.SIG_DFL)   # a background shell would hand SIGINT down ignored
child = subprocess.Popen([shadowlab, "bench", "--backend", "osmesa", "--techniques", "shadowmap", "--size", "64x48",
                          "--frames", "100000", "--out", os.path.join(tmp, "b.csv")],
                         stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
deadline = time.time() + 30
while time.time() < deadline and not glob.glob(os.path.join(tmp, "shadowlab-*", "*.so")):
    time.sleep(0.05)
time.sleep(0.3)
child.send_signal(getattr(signal, "SIG" + name))
code = child.wait(timeout=30)
print(code, len(glob.glob(os.path.join(tmp, "shadowlab-*"))))
PY
)
    expected="-$( [ $signal = INT ] && echo 2 || echo 15) 0"
    if [ "$result" = "$expected" ]; then echo "ok: SIG$signal during a run -> killed by it, scratch folder removed"
    else echo "FAIL: SIG$signal: got '$result' (exit status, folders left), want '$expected'"; failures=$((failures + 1)); fi
done

# --- issue 14: guided tours and sessions are read and checked whole before the first frame; a bad
# one exits 2 naming the file, the step and the problem (tests/test_tours.cpp has every field).
tour_step() {   # tour_step FILE STEP-JSON: a tour whose second step is STEP-JSON
    printf '{"title": "t", "steps": [{"title": "ok", "scene": "cube", "technique": "shadowmap", "caption": "c"}, %s]}\n' "$2" > "$1"
}
printf '{"title": "t", "steps": [' > "$tmp/tour-broken.json"
expect 2 "tour-broken.json" -- tour "$tmp/tour-broken.json" --out "$tmp/tour"
tour_step "$tmp/tour-technique.json" '{"title": "two", "scene": "cube", "technique": "nosuch", "caption": "c"}'
expect 2 "tour-technique.json: steps\[1\] (\"two\"): technique 'nosuch': no such technique" -- tour "$tmp/tour-technique.json" --out "$tmp/tour"
tour_step "$tmp/tour-param.json" '{"title": "two", "scene": "cube", "technique": "shadowmap", "parameters": {"kernel": 3}, "caption": "c"}'
expect 2 "tour-param.json: steps\[1\].*shadowmap has no parameter 'kernel'" -- tour "$tmp/tour-param.json" --out "$tmp/tour"
tour_step "$tmp/tour-range.json" '{"title": "two", "scene": "cube", "technique": "shadowmap", "parameters": {"resolution": 10}, "caption": "c"}'
expect 2 "tour-range.json: steps\[1\].*resolution.*out of range" -- tour "$tmp/tour-range.json" --out "$tmp/tour"
tour_step "$tmp/tour-scene.json" '{"title": "two", "scene": "nowhere", "technique": "shadowmap", "caption": "c"}'
expect 2 "tour-scene.json: steps\[1\].*scene: .*nowhere: cannot open scene file" -- tour "$tmp/tour-scene.json" --out "$tmp/tour"
tour_step "$tmp/tour-light.json" '{"title": "two", "scene": "cube", "technique": "shadowmap", "light": {"size": 90}, "caption": "c"}'
expect 2 "tour-light.json: steps\[1\].*light.size" -- tour "$tmp/tour-light.json" --out "$tmp/tour"
tour_step "$tmp/tour-view.json" '{"title": "two", "scene": "cube", "technique": "pcf", "view": "moments", "caption": "c"}'
expect_bounded 2 "tour-view.json: steps\[1\].*view 'moments': pcf has no such view" -- tour --backend osmesa --size 64x48 "$tmp/tour-view.json" --out "$tmp/tour"
[ ! -e "$tmp/tour/step-01.png" ] || { echo "FAIL: a slide was drawn before the tour was refused"; failures=$((failures + 1)); }
expect 2 "no-such-tour: no such tour file" -- tour no-such-tour --out "$tmp/tour"
# A step's path (issue 12's paths): a built-in name or a file relative to the tour, checked before
# the first slide, in `tour` and in the window.
tour_step "$tmp/tour-pathname.json" '{"title": "two", "scene": "cube", "technique": "shadowmap", "path": "dolyy", "caption": "c"}'
expect 2 "tour-pathname.json: steps\[1\] (\"two\"): path 'dolyy': not a built-in path (orbit, dolly, sweep, walk, static)" -- tour "$tmp/tour-pathname.json" --out "$tmp/tour"
expect 2 "--tour: .*tour-pathname.json: steps\[1\].*path 'dolyy'" -- --backend osmesa --tour "$tmp/tour-pathname.json" --frames 2 --screenshot "$tmp/s.png"
tour_step "$tmp/tour-pathfile.json" '{"title": "two", "scene": "cube", "technique": "shadowmap", "path": "paths/missing.json", "caption": "c"}'
expect 2 "tour-pathfile.json: steps\[1\] (\"two\"): path '$tmp/paths/missing.json'" -- tour "$tmp/tour-pathfile.json" --out "$tmp/tour"
mkdir -p "$tmp/paths"
echo '{"keyframes": [{"time": 0, "light": {"position": [0, 5, 0]}}, {"time": 1, "light": {"position": [1, 5, 0]}}]}' > "$tmp/paths/lamp.json"
tour_step "$tmp/tour-pathlight.json" '{"title": "two", "scene": "cube", "technique": "shadowmap", "path": "paths/lamp.json", "caption": "c"}'
expect 2 "tour-pathlight.json: steps\[1\].*paths/lamp.json': moves the light by position, but scene 'cube' has a directional light" -- tour "$tmp/tour-pathlight.json" --out "$tmp/tour"
echo '{"keyframes": [{"time": 0, "camra": {}}]}' > "$tmp/paths/typo.json"
tour_step "$tmp/tour-pathtypo.json" '{"title": "two", "scene": "cube", "technique": "shadowmap", "path": "paths/typo.json", "caption": "c"}'
expect 2 "tour-pathtypo.json: steps\[1\].*typo.json.*camra" -- tour "$tmp/tour-pathtypo.json" --out "$tmp/tour"
tour_step "$tmp/tour-patherror.json" '{"title": "two", "scene": "cube", "technique": "shadowmap", "path": "orbit", "view": "error", "caption": "c"}'
expect 2 "tour-patherror.json: steps\[1\].*path 'orbit': the error view" -- tour "$tmp/tour-patherror.json" --out "$tmp/tour"
# The window checks a step's debug view when the tour is loaded, before the first step is shown.
expect_bounded 2 "tour-view.json: steps\[1\].*view 'moments': pcf has no such view" -- --backend osmesa --size 64x48 --tour "$tmp/tour-view.json" --frames 2 --screenshot "$tmp/s-view.png"
[ ! -e "$tmp/s-view.png" ] || { echo "FAIL: the window drew the tour before refusing its view"; failures=$((failures + 1)); }
# The window's --tour and --session, with and without a display.
expect 2 "--tour: .*tour-range.json: steps\[1\]" -- --backend osmesa --tour "$tmp/tour-range.json" --frames 2 --screenshot "$tmp/s.png"
tour_step "$tmp/tour-ok.json" '{"title": "two", "scene": "hover", "technique": "pcf", "caption": "c"}'
expect 2 "--tour-step 9: .* has steps 1 to 2" -- --backend osmesa --tour "$tmp/tour-ok.json" --tour-step 9 --frames 2
expect 2 "--tour: no display" -- --backend osmesa --tour "$tmp/tour-ok.json"
echo '{"title": "s", "scene": "cube", "technique": "shadowmap", "parameters": {"slope_bias": -1}, "caption": "c"}' > "$tmp/session-bad.json"
expect 2 "--session: .*session-bad.json.*slope_bias.*out of range" -- --backend osmesa --session "$tmp/session-bad.json" --frames 2
echo '{"title": "s", "scene": "cube", "technique": "shadowmap", "caption": "c", "steps": []}' > "$tmp/session-tour.json"
expect 2 "session-tour.json: unknown field 'steps'" -- --backend osmesa --session "$tmp/session-tour.json" --frames 2

[ $failures = 0 ] || { echo "$failures failure(s)"; exit 1; }
echo "all CLI error checks passed"
