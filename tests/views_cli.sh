#!/usr/bin/env bash
# The debug views of issue 14 headless, on OSMesa: `render --view focus-body` draws B's white
# outline (fit = focus-body) and none with the scene fit; `render --view kernel --probe X,Y` draws
# the filter kernel around pixel X,Y and prints its numbers (pcf's n x n box is n texels wide, n^2
# samples; the yellow box is drawn around X,Y); bad --probe values exit 2 naming the option.
set -uo pipefail
shadowlab=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
unset DISPLAY WAYLAND_DISPLAY
python=/usr/bin/python3   # Debian's, with python3-pil
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

r=(render --backend osmesa --scene cube --size 320x240 --frames 1)
expect 2 "--probe 'x,1': expected X,Y" -- "${r[@]}" -t pcf --view kernel --probe x,1 --out "$tmp/a.png"
expect 2 "--probe '12': expected X,Y" -- "${r[@]}" -t pcf --view kernel --probe 12 --out "$tmp/a.png"
expect 2 "--probe '-3,4': expected X,Y" -- "${r[@]}" -t pcf --view kernel --probe=-3,4 --out "$tmp/a.png"
expect 2 "--probe 320,10: outside the 320x240 image" -- "${r[@]}" -t pcf --view kernel --probe 320,10 --out "$tmp/a.png"
expect 2 "--probe: the kernel view draws the probe" -- "${r[@]}" -t pcf --view lit --probe 10,10 --out "$tmp/a.png"
[ ! -e "$tmp/a.png" ] || { echo "FAIL: an image was written for a bad --probe"; failures=$((failures + 1)); }

# A ground pixel below the cube: pcf's box of 5 x 5 taps one texel apart is 5 texels wide.
expect 0 "kernel=box n=5 kernel_texels=5.0000 samples=25" -- "${r[@]}" -t pcf --set kernel=5 --set offset_scale=1 \
    --set hardware_filter=0 --set resolution=256 --view kernel --probe 160,200 --out "$tmp/box.png"
expect 0 "kernel=box n=3 kernel_texels=4.0000 samples=9" -- "${r[@]}" -t pcf --set kernel=3 --set offset_scale=1 \
    --set hardware_filter=1 --set resolution=256 --view kernel --probe 160,200 --out "$tmp/box3.png"
expect 0 "kernel=pcss .* search_samples=36" -- "${r[@]}" -t pcss --set search_grid=6 --set search_bound=0 \
    --view kernel --probe 160,200 --out "$tmp/pcss.png"
expect 0 "wrote" -- "${r[@]}" -t shadowmap --set fit=focus-body --view focus-body --out "$tmp/body.png"
expect 0 "wrote" -- "${r[@]}" -t shadowmap --set fit=scene --view focus-body --out "$tmp/scene.png"

"$python" - "$tmp" <<'PY' || failures=$((failures + 1))
import sys
from PIL import Image
tmp = sys.argv[1]
def count(path, rgb, tol, box=None):
    im = Image.open(path).convert("RGB")
    w, h = im.size
    px = im.load()
    n = 0
    for y in range(h):
        for x in range(w):
            if box and not (box[0] <= x <= box[2] and box[1] <= y <= box[3]):
                continue
            p = px[x, y]
            if all(abs(p[c] - rgb[c]) <= tol for c in range(3)):
                n += 1
    return n
yellow = (255, 217, 0)
near = count(f"{tmp}/box.png", yellow, 8, (160 - 40, 200 - 40, 160 + 40, 200 + 40))
# The magnified inset (issue 29) at the top right (the probe is in the lower half) shows the box
# again, larger; every other yellow pixel is near the probe.
inset = count(f"{tmp}/box.png", yellow, 8, (200, 0, 319, 130))
total = count(f"{tmp}/box.png", yellow, 8)
assert near > 8 and near + inset == total, f"the box is drawn around the probe (160,200): {near} of {total} yellow pixels near it, {inset} in the inset"
assert inset > near, f"the inset does not magnify the box ({inset} yellow pixels in it, {near} around the probe)"
white_body = count(f"{tmp}/body.png", (255, 255, 255), 6)
white_scene = count(f"{tmp}/scene.png", (255, 255, 255), 6)
assert white_body > 100 and white_scene < 5, f"B's outline: {white_body} white pixels with fit=focus-body, {white_scene} with fit=scene"
print(f"ok: box drawn around the probe ({near} px), B outline {white_body} px, none without B ({white_scene})")
PY
[ $failures = 0 ] || { echo "$failures failure(s)"; exit 1; }
echo "all debug-view CLI checks passed"
