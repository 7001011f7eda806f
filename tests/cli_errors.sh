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
# Virtual shadow maps (issue 30): the plugin's ranges and options, named.
expect 2 "parameter 'virtual_size': 65536 is out of range" -- render --backend osmesa -t virtual-sm --set virtual_size=65536 --out "$tmp/a.png"
expect 2 "parameter 'filter': 'box' is not one of hardware, pcf" -- render --backend osmesa -t virtual-sm --set filter=box --out "$tmp/a.png"
# Contact shadows (issue 30): every host.contact_* key checked, in --set, sweeps and stress --set.
expect 2 "parameter 'contact_shadows': -1 is out of range" -- render --backend osmesa -t shadowmap --set host.contact_shadows=-1 --out "$tmp/a.png"
expect 2 "host.contact_steps=...: parameter 'contact_steps': 65 is out of range" -- bench --backend osmesa --techniques shadowmap --sweep host.contact_steps=16,65 --out "$tmp/b.json"
expect 2 "host.contact_thickness=0: parameter 'contact_thickness': 0 is out of range" -- stress --backend osmesa --techniques shadowmap --cases contact-shadows-plate --set host.contact_thickness=0 --out "$tmp/stress-contact"
expect 2 "parameter 'contact_jitter': 1.5 is out of range" -- eval --backend osmesa -t shadowmap --set host.contact_jitter=1.5
# The depth pre-pass (issue 32): auto | on | off, 0/1 and the bare flag of older command lines.
expect 2 "--depth-prepass 'sometimes': expected auto, on or off" -- render --backend osmesa -t shadowmap --depth-prepass sometimes --out "$tmp/a.png"
expect 2 "host.depth_prepass=...: parameter 'depth_prepass': 'maybe' is not one of off, on, auto" -- bench --backend osmesa --techniques shadowmap --sweep host.depth_prepass=auto,maybe --out "$tmp/b.json"
for form in "--depth-prepass" "--depth-prepass=on" "--depth-prepass 1" "--sweep host.depth_prepass=on"; do
    # shellcheck disable=SC2086
    expect 0 "wrote" -- bench --backend osmesa --size 64x48 --techniques shadowmap --frames 2 --warmup 1 $form --out "$tmp/prepass.json"
    if ! grep -q '"depth_prepass_mode": "on"' "$tmp/prepass.json" || ! grep -q '"depth_prepass": 1' "$tmp/prepass.json"; then
        echo "FAIL: bench $form: the row does not say the pre-pass was on"; failures=$((failures + 1))
    fi
done
expect 0 "wrote" -- bench --backend osmesa --size 64x48 --techniques shadowmap --frames 2 --warmup 1 --out "$tmp/prepass.json"
grep -q '"depth_prepass_mode": "auto"' "$tmp/prepass.json" && grep -q '"depth_prepass": 0' "$tmp/prepass.json" ||
    { echo "FAIL: bench on cube by default: not auto, or auto chose the pre-pass"; failures=$((failures + 1)); }
expect 2 "no such technique" -- render --backend osmesa -t nonexistent --out "$tmp/a.png"
# --technique and --set are checked against the descriptors before a GL context exists: with a
# backend that cannot start here (glfw, no display) the option is still what is named.
for cmd in "render --out $tmp/a.png" "eval"; do
    # shellcheck disable=SC2086
    DISPLAY= WAYLAND_DISPLAY= expect 2 "resolution=10: parameter 'resolution': 10 is out of range" -- $cmd --backend glfw -t shadowmap --set resolution=10
    # shellcheck disable=SC2086
    DISPLAY= WAYLAND_DISPLAY= expect 2 "--technique 'nonesuch': no such technique" -- $cmd --backend glfw -t nonesuch
done
DISPLAY= WAYLAND_DISPLAY= expect 2 "--techniques: no technique 'nonesuch'" -- stress --backend glfw --techniques nonesuch --out "$tmp/stress-glfw"
expect 2 "expected glfw, egl or osmesa" -- render --backend vulkan --out "$tmp/a.png"
expect 2 "WIDTHxHEIGHT" -- render --backend osmesa --size 12by3 --out "$tmp/a.png"
expect 2 "--view 'nope': shadowmap has no such view (views: lit, visibility, error, footprint, texel-grid, coverage, focus-body, kernel, reference, 'shadow map')" -- render --backend osmesa -t shadowmap --view nope --out "$tmp/a.png"
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
expect 2 "--sweep excludes --path" -- bench --backend osmesa --techniques shadowmap --path orbit --sweep resolution=512,1024 --out "$tmp/p.json"
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
printf '{"cases": [{"id": "eye-on-target", "title": "t", "scene": "cube", "camera": {"position": [0.4, 0.3, -0.3]}, "metric": "false_shadow", "threshold": 0.1, "claim": "c", "source": "s"}]}' > "$tmp/cases-camera.json"
expect 2 "cases-camera.json: case eye-on-target: camera (with the target of scene 'cube'): the target is at the camera position" -- stress --backend osmesa --techniques shadowmap --cases-file "$tmp/cases-camera.json" --out "$tmp/stress"
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
expect_bounded 2 "--sweep resolution=...: shadowmap: parameter 'resolution': 'abc' is not a number" -- "${bench[@]}" --techniques shadowmap --sweep resolution=256,abc --depth-floor
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
# A plugin folder that does not exist, or holds no plugin: bad input, naming the folder.
SHADOWLAB_PLUGIN_DIR="$tmp/no-such-folder" expect_bounded 2 "no technique plugins found in .*no-such-folder" -- "${render[@]}"

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
    # SIGINT stops the run cleanly (exit 130, util/progress.h); SIGTERM kills it. Either way the folder goes.
    expected="$( [ $signal = INT ] && echo 130 || echo -15) 0"
    if [ "$result" = "$expected" ]; then echo "ok: SIG$signal during a run -> exit $expected, scratch folder removed"
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

# --- issue 31: one rule for every reader. Each check: exit 2, the message names the file or option.
# A step is checked alike in a tour and in a session file (here: its view, before the first frame).
echo '{"title": "s", "scene": "cube", "technique": "pcf", "view": "moments", "caption": "c"}' > "$tmp/session-view.json"
expect_bounded 2 "session-view.json.*view 'moments': pcf has no such view (views: lit, visibility, error, footprint" -- --backend osmesa --size 64x48 --session "$tmp/session-view.json" --frames 2 --screenshot "$tmp/s-session.png"
[ ! -e "$tmp/s-session.png" ] || { echo "FAIL: the window drew the session before refusing its view"; failures=$((failures + 1)); }
# A path keyframe gets a scene's camera and light checks, and so does every frame between keyframes.
printf '{"keyframes": [{"time": 0, "camera": {"position": [1, 2, 3], "target": [1, 2, 3]}}, {"time": 1, "camera": {"position": [0, 2, 3]}}]}' > "$tmp/path-same.json"
expect 2 "path-same.json: keyframes\[0\].camera: the target is at the camera position" -- "${pathrender[@]}" --path "$tmp/path-same.json" --out "$tmp/frames31"
printf '{"keyframes": [{"time": 0, "light": {"direction": [1, -1, 0]}}, {"time": 1, "light": {"direction": [-1, 1, 0]}}], "frames": 3}' > "$tmp/path-zero.json"
expect 2 "path-zero.json: frame 1 (time 0.5): the light's direction passes through zero" -- "${pathrender[@]}" --path "$tmp/path-zero.json" --out "$tmp/frames31"
printf '{"keyframes": [{"time": 0, "camera": {"position": [0, 9, 0], "target": [0, 0, 0]}}], "frames": 2}' > "$tmp/path-up.json"
expect 2 "path-up.json: frame 0 (time 0): the camera looks straight along its up vector" -- "${pathrender[@]}" --path "$tmp/path-up.json" --out "$tmp/frames31"
echo '{"camera": {"position": [0, 9, 0], "target": [0, 0, 0]}, "objects": [{"shape": "box"}]}' > "$tmp/camera-up.json"
expect 2 "camera-up.json: camera.up: the camera looks straight along its up vector" -- "${render[@]}" --scene "$tmp/camera-up.json"
tour_step "$tmp/tour-camera-up.json" '{"title": "two", "scene": "cube", "technique": "shadowmap", "camera": {"position": [0, 9, 0], "target": [0, 0, 0]}, "caption": "c"}'
expect 2 "tour-camera-up.json: steps\[1\] (\"two\"): camera: the camera looks straight along its up vector" -- tour "$tmp/tour-camera-up.json" --out "$tmp/tour31"
# A repeat block's grid is held to the cell limit with a count too.
echo '{"objects": [{"shape": "box", "repeat": {"count": 2, "grid": [1000000, 1000000]}}]}' > "$tmp/grid.json"
expect_bounded 2 "grid.json: objects\[0\].repeat.grid: 1000000 x 1000000 = 1000000000000 cells, more than 1000000" -- "${render[@]}" --scene "$tmp/grid.json"
# Options: a common option a command does not use, empty values and list items, options that need another.
expect 2 "--set: \`report\` does not use it" -- report --set resolution=512 --out "$tmp/report31"
expect 2 "--scene: \`list\` does not use it" -- list --scene cube
expect 2 "--technique: \`stress\` does not use it (use --techniques)" -- stress --technique shadowmap --out "$tmp/stress31"
expect 2 "--scene: \`tour\` does not use it" -- tour shadow-mapping --scene cube --out "$tmp/tour31"
expect 2 "--translucent-layers: \`render\` does not use it (only the accuracy views" -- render --translucent-layers 2 --out "$tmp/a.png"
expect 2 "--reference-device: \`bench\` does not use it (only --accuracy traces the reference)" -- bench --techniques shadowmap --reference-device gpu --out "$tmp/b.csv"
expect 2 "--set nosuch=1: 'nosuch' is no parameter of the techniques measured (shadowmap)" -- stress --backend osmesa --techniques shadowmap --set nosuch=1 --out "$tmp/stress31"
expect 2 "--techniques: an empty value" -- bench --techniques '' --out "$tmp/b.csv"
expect 2 "--scene: an empty value" -- render --scene '' --out "$tmp/a.png"
expect 2 "--budget: an empty value" -- render --budget '' --out "$tmp/a.png"
expect 2 "--techniques 'shadowmap,': item 2 of the list is empty" -- bench --techniques shadowmap, --out "$tmp/b.csv"
expect 2 "--sweep resolution=... '512,,1024': item 2 of the list is empty" -- bench --techniques shadowmap --sweep resolution=512,,1024 --out "$tmp/b.csv"
expect 2 "--cases ',acne-5': item 1 of the list is empty" -- stress --techniques shadowmap --cases ,acne-5 --out "$tmp/stress31"
expect 2 "--budget 'objects=10,,triangles=5': item 2 of the list is empty" -- "${render[@]}" --budget objects=10,,triangles=5
expect 2 "--path-frames requires --path" -- render --path-frames 3 --out "$tmp/a.png"
expect 2 "--path-frames requires --path" -- bench --path-frames 3 --out "$tmp/b.csv"
expect 2 "--samples: only the soft reference has it" -- eval --reference hard --samples 64
expect 2 "--reference-adaptive: only the soft reference has it" -- eval --reference hard --reference-adaptive off
expect 2 "--wipe requires --compare" -- render --wipe 0.3 --out "$tmp/a.png"
expect 2 "--wipe: places the divider of --compare-layout wipe" -- render --compare shadowmap,pcf --wipe 0.3 --out "$tmp/a.png"
expect 2 "--samples: only the accuracy views trace the reference" -- render --samples 64 --out "$tmp/a.png"
expect 2 "--samples: only --accuracy traces the reference" -- bench --techniques shadowmap --samples 64 --out "$tmp/b.csv"
expect 2 "--tour-step requires --tour" -- --backend osmesa --tour-step 2 --frames 1
expect 2 "--techniques excludes --spec" -- bench --spec assets/bench/quick.json --techniques shadowmap --out "$tmp/b.csv"
expect 2 "--set: the spec (--spec) sets its parameters itself" -- bench --spec assets/bench/quick.json --set resolution=512 --out "$tmp/b.csv"
# Repeated keys: in JSON files (every reader), --budget, --set, --sweep.
echo '{"objects": [{"shape": "box", "size": [1, 1, 1], "size": [2, 2, 2]}]}' > "$tmp/dup.json"
expect 2 "dup.json: duplicate key \"size\" in \"/objects/0\"" -- "${render[@]}" --scene "$tmp/dup.json"
echo '{"techniques": ["shadowmap"], "frames": 2, "frames": 3}' > "$tmp/dup-spec.json"
expect 2 "dup-spec.json: duplicate key \"frames\" in the top-level object" -- bench --spec "$tmp/dup-spec.json" --out "$tmp/b.csv"
tour_step "$tmp/tour-dup.json" '{"title": "two", "scene": "cube", "technique": "shadowmap", "parameters": {"resolution": 512, "resolution": 1024}, "caption": "c"}'
expect 2 "tour-dup.json: duplicate key \"resolution\" in \"/steps/1/parameters\"" -- tour "$tmp/tour-dup.json" --out "$tmp/tour31"
echo '{"title": "s", "scene": "cube", "technique": "shadowmap", "view": "lit", "view": "visibility", "caption": "c"}' > "$tmp/session-dup.json"
expect 2 "session-dup.json: duplicate key \"view\"" -- --backend osmesa --session "$tmp/session-dup.json" --frames 2
printf '{"keyframes": [{"time": 0, "time": 1}]}' > "$tmp/path-dup.json"
expect 2 "path-dup.json: duplicate key \"time\" in \"/keyframes/0\"" -- "${pathrender[@]}" --path "$tmp/path-dup.json" --out "$tmp/frames31"
expect 2 "--budget 'objects=10,objects=20': the key 'objects' is given twice" -- "${render[@]}" --budget objects=10,objects=20
expect 2 "--set resolution=...: the key is given twice" -- "${render[@]}" --set resolution=512 --set resolution=1024
expect 2 "--sweep resolution=...: the key is swept twice" -- bench --techniques shadowmap --sweep resolution=512 --sweep resolution=1024 --out "$tmp/b.csv"
# Outputs are checked before the first frame: a file where the folder should be is found at once.
touch "$tmp/afile"
SECONDS=0
expect_bounded 2 "--out $tmp/afile: cannot create the folder $tmp/afile" -- report --backend osmesa --out "$tmp/afile"
[ "$SECONDS" -lt 20 ] || { echo "FAIL: report took ${SECONDS}s to refuse its output folder (measured first?)"; failures=$((failures + 1)); }
expect_bounded 2 "--out $tmp/afile/b.csv: cannot create the folder" -- bench --backend osmesa --techniques shadowmap --out "$tmp/afile/b.csv"
expect_bounded 2 "--out $tmp/afile/frames: cannot create the folder" -- "${pathrender[@]}" --path dolly --out "$tmp/afile/frames"
expect_bounded 2 "--out $tmp/afile/s: cannot create the folder" -- stress --backend osmesa --techniques shadowmap --out "$tmp/afile/s"
expect_bounded 2 "--out $tmp: a folder, expected a file" -- render --backend osmesa --size 64x48 --out "$tmp"
# Messages keep their subject: a spec file's content errors name the file; a NUL byte is shown.
echo '{"techniques": ["nosuch"]}' > "$tmp/spec-tech.json"
expect 2 "spec-tech.json: techniques: no technique 'nosuch'" -- bench --backend osmesa --spec "$tmp/spec-tech.json" --out "$tmp/b.csv"
echo '[{"techniques": ["shadowmap"]}, {"techniques": ["shadowmap"], "sweep": {"resolutoin": [512]}}]' > "$tmp/spec-sweep.json"
expect 2 "spec-sweep.json: spec 1: sweep.resolutoin: 'resolutoin' is no parameter" -- bench --backend osmesa --spec "$tmp/spec-sweep.json" --out "$tmp/b.csv"
echo '{"techniques": ["shadowmap"], "scenes": ["nowhere"]}' > "$tmp/spec-scene.json"
expect 2 "spec-scene.json: scenes 'nowhere'" -- report --backend osmesa --spec "$tmp/spec-scene.json" --out "$tmp/report31"
printf '{"objects": [{"shape": "box"}], "na\\u0000me": "x"}' > "$tmp/nul.json"
expect 2 "nul.json: na\\\\x00me: unknown field (did you mean 'name'?)" -- "${render[@]}" --scene "$tmp/nul.json"
printf 'v 0 0 0\nv 1 0 0\nv 0 0 -1\nf 1 2 3x\000tail-of-the-line\n' > "$tmp/nul.obj"
echo '{"objects": [{"shape": "obj", "file": "nul.obj"}]}' > "$tmp/nul-obj.json"
expect 2 "nul.obj:4: OBJ parse error: '3x\\\\x00tail-of-the-line' is not a vertex index" -- "${render[@]}" --scene "$tmp/nul-obj.json"

# Ctrl-C: a long run stops cleanly, writes what it did and exits 130 (util/progress.h).
interrupt() {   # interrupt WHAT WAIT-FOR CHECK-SCRIPT -- ARGS...: SIGINT once the file WAIT-FOR exists (or after N s: "after:N")
    local what=$1 wait_for=$2 check=$3
    shift 4
    if python3 - "$shadowlab" "$wait_for" "$check" "$@" <<'PY'
import os, signal, subprocess, sys, time
shadowlab, wait_for, check = sys.argv[1:4]
signal.signal(signal.SIGINT, signal.SIG_DFL)
child = subprocess.Popen([shadowlab] + sys.argv[4:], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
deadline = time.time() + (float(wait_for[6:]) if wait_for.startswith("after:") else 120)
while time.time() < deadline and (wait_for.startswith("after:") or not os.path.exists(wait_for)) and child.poll() is None:
    time.sleep(0.05)
time.sleep(0.5)
child.send_signal(signal.SIGINT)
_, err = child.communicate(timeout=60)
assert child.returncode == 130, (child.returncode, err[-2000:])
assert "interrupted (Ctrl-C)" in err, err[-2000:]
exec(check)
PY
    then echo "ok: $what: SIGINT -> exit 130, partial results written"
    else echo "FAIL: $what: SIGINT"; failures=$((failures + 1)); fi
}
interrupt "bench" "$tmp/int-bench.json" '
import json
rows = json.load(open(sys.argv[2]))
assert 1 <= len(rows) < 40, len(rows)
assert all(r["technique"] == "shadowmap" for r in rows), rows' -- \
    bench --backend osmesa --size 64x48 --techniques shadowmap --frames 400 --warmup 0 \
    --sweep resolution=256,272,288,304,320,336,352,368,384,400,416,432,448,464,480,496,512,528,544,560,576,592,608,624,640,656,672,688,704,720,736,752,768,784,800,816,832,848,864,880 \
    --out "$tmp/int-bench.json"
interrupt "render --path" "$tmp/int-frames/frame_00003.png" '
import glob
frames = sorted(glob.glob(sys.argv[2].rsplit("/", 1)[0] + "/frame_*.png"))
assert 4 <= len(frames) < 100000, len(frames)
assert frames[0].endswith("frame_00000.png") and frames[-1].endswith("frame_%05d.png" % (len(frames) - 1)), frames[-3:]' -- \
    render --backend osmesa --size 64x48 -t shadowmap --path dolly --path-frames 100000 --out "$tmp/int-frames"
interrupt "bench --path" "after:4" '
import json
rows = json.load(open(sys.argv[sys.argv.index("--out") + 1]))
assert len(rows) == 1 and rows[0]["interrupted"] is True, rows
assert 1 <= rows[0]["frames"] < 100000 and rows[0]["path_frames"] == 100000, rows[0]["frames"]
assert len(rows[0]["frame_ms_per_frame"]) == rows[0]["frames"]' -- \
    bench --backend osmesa --size 64x48 --techniques shadowmap --path orbit --path-frames 100000 --warmup 0 --out "$tmp/int-path.json"

[ $failures = 0 ] || { echo "$failures failure(s)"; exit 1; }
echo "all CLI error checks passed"
