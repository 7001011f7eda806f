#!/usr/bin/env bash
# The kernel debug view in the real window under Xvfb (issue 14), driven by xdotool: a session
# shows pcf's kernel view with the UI hidden; the mouse hovers two ground points in turn (no button:
# the camera stays) and F12 saves each; in each screenshot the yellow box of the 7 x 7 PCF kernel
# is drawn around the mouse and nowhere else, so the probe follows the pixel under the mouse.
set -euo pipefail
if [ "${1:-}" != --inside ]; then
  exec "$1" -a -s "-screen 0 1280x800x24 -noreset" bash "$0" --inside "$2"
fi
shadowlab=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"

cat > kernel.json <<'JSON'
{"title": "kernel", "scene": "cube", "technique": "pcf",
 "parameters": {"kernel": 7, "offset_scale": 1, "hardware_filter": false, "resolution": 1024},
 "view": "kernel", "caption": "PCF's box around the pixel under the mouse."}
JSON
for _ in $(seq 50); do xdotool getmouselocation >/dev/null 2>&1 && break; sleep 0.2; done   # the server answers
"$shadowlab" --backend glfw --size 960x540 --hide-ui --session kernel.json 2>app.log &
app=$!
window=""
for _ in $(seq 150); do
  window=$(xdotool search --name "^shadowlab$" 2>/dev/null | head -1 || true)
  [ -n "$window" ] && break
  sleep 0.2
done
[ -n "$window" ] || { echo "FAIL: no window"; cat app.log; kill $app; exit 1; }
sleep 3
xdotool windowfocus --sync "$window" 2>/dev/null || true
shots() { { ls screenshots/*.png 2>/dev/null || true; } | wc -l; }
for point in "480 470" "250 430"; do
  read -r x y <<<"$point"
  xdotool mousemove --window "$window" "$x" "$y"
  sleep 1.5   # a few frames with the probe there
  before=$(shots)
  xdotool key F12
  for _ in $(seq 300); do [ "$(shots)" -gt "$before" ] && break; sleep 0.2; done
done
xdotool key Escape
for _ in $(seq 300); do kill -0 $app 2>/dev/null || break; sleep 0.2; done
if kill -0 $app 2>/dev/null; then echo "FAIL: Escape did not quit"; kill $app; exit 1; fi
wait $app || { cat app.log; echo "FAIL: exit status $?"; exit 1; }
[ "$(shots)" = 2 ] || { cat app.log; echo "FAIL: $(shots) screenshots, expected 2"; exit 1; }

/usr/bin/python3 - $(ls screenshots/*.png | sort) <<'PY'
import sys
from PIL import Image
expected = [(480, 470), (250, 430)]
for path, (mx, my) in zip(sys.argv[1:], expected):
    im = Image.open(path).convert("RGB")
    w, h = im.size
    px = im.load()
    every = [(x, y) for y in range(h) for x in range(w)
             if abs(px[x, y][0] - 255) <= 8 and abs(px[x, y][1] - 217) <= 8 and px[x, y][2] <= 8]
    # The magnified inset (issue 29) sits at the view's top right when the probe is in the lower
    # half: the box's pixels there are the inset's, counted apart.
    inset = [p for p in every if p[0] >= 700 and p[1] <= 260]
    yellow = [p for p in every if p not in inset]
    assert len(yellow) > 8, f"{path}: no kernel box drawn ({len(yellow)} yellow pixels)"
    assert len(inset) > len(yellow), f"{path}: the inset does not magnify the box ({len(inset)} yellow pixels, {len(yellow)} in the view)"
    far = [p for p in yellow if abs(p[0] - mx) > 60 or abs(p[1] - my) > 60]
    cx = sum(p[0] for p in yellow) / len(yellow)
    cy = sum(p[1] for p in yellow) / len(yellow)
    assert not far and abs(cx - mx) <= 8 and abs(cy - my) <= 8, \
        f"{path}: the box is centred at ({cx:.1f}, {cy:.1f}), the mouse at ({mx}, {my}); {len(far)} yellow pixels far from it"
    print(f"ok: {path}: the kernel box ({len(yellow)} px) centred at ({cx:.1f}, {cy:.1f}), the mouse at ({mx}, {my}); "
          f"{len(inset)} px in the magnified inset")
PY
