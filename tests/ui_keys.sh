#!/usr/bin/env bash
# The window's keys under Xvfb (issue 14), driven by xdotool: F12 twice saves two screenshots
# named by scene, technique and time under screenshots/ (never out/, never overwriting: they used
# to be out/screenshot-000.png again every session), H hides the panel (the third screenshot
# shows the view across the whole window), Escape quits with 0. Then a wipe comparison: the
# divider's handle dragged from the middle of the view to the right moves the divider there.
set -euo pipefail
# Everything runs under one X server (xvfb-run -a picks a free display; starting a second one
# for the second run raced with other tests' servers; -noreset: the server does not reset, and
# refuse connections meanwhile, when the first window closes).
if [ "${1:-}" != --inside ]; then
  exec "$1" -a -s "-screen 0 1280x800x24 -noreset" bash "$0" --inside "$2"
fi
shadowlab=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"

# drive ACTIONS APP-ARGS...: starts the window, waits for it, runs the
# xdotool ACTIONS (with $window set; they end by quitting it) and checks that it exits with 0.
cat >drive.sh <<'SH'
set -euo pipefail
actions=$1 shadowlab=$2
shift 2
for _ in $(seq 50); do xdotool getmouselocation >/dev/null 2>&1 && break; sleep 0.2; done   # the server answers
"$shadowlab" --backend glfw --size 960x540 --quiet "$@" &
app=$!
window=""
for _ in $(seq 150); do
  window=$(xdotool search --name "^shadowlab$" 2>/dev/null | head -1 || true)
  [ -n "$window" ] && break
  sleep 0.2
done
[ -n "$window" ] || { echo "FAIL: no window"; kill $app; exit 1; }
sleep 3
xdotool windowfocus --sync "$window" 2>/dev/null || true
eval "$actions"
for _ in $(seq 50); do kill -0 $app 2>/dev/null || break; sleep 0.2; done
if kill -0 $app 2>/dev/null; then echo "FAIL: Escape did not quit"; kill $app; exit 1; fi
wait $app
SH
drive() { bash drive.sh "$@"; }

mkdir -p screenshots
# A screenshot of an earlier session must survive.
touch -d '2020-01-01' screenshots/keep.png
drive 'xdotool mousemove 900 300   # over the view, not the panel
       for key in F12 F12 h F12 Escape; do xdotool key "$key"; sleep 1.5; done' \
  "$shadowlab" -t shadowmap --scene contact
[ ! -e out ] || { echo "FAIL: screenshots went to out/"; exit 1; }
[ -f screenshots/keep.png ] || { echo "FAIL: an earlier screenshot was removed"; exit 1; }
/usr/bin/python3 - <<'PY'
import glob, os
import numpy as np
from PIL import Image
shots = sorted(glob.glob('screenshots/contact-shadowmap-*.png'), key=os.path.getmtime)
assert len(shots) == 3, f'expected 3 screenshots, found {shots}'
assert len(set(shots)) == 3
images = [np.asarray(Image.open(s).convert('RGB')).astype(int) for s in shots]
for image in images:
    assert image.shape == (540, 960, 3), image.shape
panel = slice(0, 300)
# With the panel: its left part is ImGui's window (dark, with text); hidden: the scene is there.
with_panel, hidden = images[1][:, panel], images[2][:, panel]
assert np.abs(with_panel - hidden).mean() > 5, 'H did not hide the panel'
assert len({tuple(p) for p in hidden[::6, ::6].reshape(-1, 3)}) > 30, 'the view does not fill the window with the panel hidden'
print('ok:', ', '.join(os.path.basename(s) for s in shots))
PY

# The wipe: 960x540 window, 360 px panel, so the view spans x 360..960 and the divider starts at
# 660 with its handle at mid-height; drag it to x 860.
rm -rf screenshots
drive 'xdotool mousemove --window "$window" 660 270; sleep 1
       xdotool mousedown 1; sleep 1
       for x in 700 760 820 860; do xdotool mousemove --window "$window" $x 270; sleep 0.5; done
       sleep 2; xdotool mouseup 1; sleep 1
       xdotool mousemove --window "$window" 500 500; sleep 1
       xdotool key F12; sleep 2
       xdotool key Escape' \
  "$shadowlab" -t shadowmap --compare pcss --compare-layout wipe --scene dragon-like
/usr/bin/python3 - <<'PY'
import glob
import numpy as np
from PIL import Image
shots = glob.glob('screenshots/dragon-like-shadowmap-vs-pcss-*.png')
assert len(shots) == 1, shots
image = np.asarray(Image.open(shots[0]).convert('RGB')).astype(int)
# The divider: a white line down the sky, the column with the most near-white pixels in the view.
sky = image[20:120, 360:960]
white = (sky.min(axis=2) > 220).sum(axis=0)
column = 360 + int(white.argmax())
assert white.max() > 80, 'no divider line found'
assert abs(column - 860) <= 12, f'divider at x={column}, expected about 860 after the drag (it started at 660)'
print(f'ok: wipe divider dragged to x={column}')
PY
