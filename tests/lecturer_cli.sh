#!/usr/bin/env bash
# The window a lecturer uses, without a display (issue 29), on OSMesa:
#   - presenter mode drawn offscreen: no panel, the tour step's caption in a large box over the
#     bottom of the view and the figures box beside it (absent from the same slide without it);
#   - `render --path P --export FILE.gif|.mp4` and the window's `--export` with --frames (a session
#     saved on a path, played again): the frames counted in the encoded file, and they move;
#   - --export refused with exit 2 naming the option: no ffmpeg on PATH, a format it does not
#     know, without --path (render) or without --frames (window);
#   - a grid of four techniques: the same technique four times gives four equal quarters, four
#     techniques four labelled quarters that differ; more than four, or a grid in a wipe, exit 2;
#   - the debug views' legends: the footprint's colour bar, a swatch per cascade in the coverage
#     view, the focus-body view saying it has no B without fit = focus-body, the texel grid without
#     a wash; the kernel view without --probe probes a shadow edge, and the README's example probe
#     lands in a penumbra;
#   - a path played outside a tour (--play-path, the panel's "Paths") at --path-speed 2.
set -euo pipefail
shadowlab=$1
source_dir=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
unset DISPLAY WAYLAND_DISPLAY
python=/usr/bin/python3   # Debian's, with python3-pil
cd "$tmp"

fail() { echo "FAIL: $*"; exit 1; }

# expect CODE TEXT -- ARGS: exit code CODE and TEXT in stderr (shadowlab run with $run_path as
# its PATH when set).
run_path=""
expect() {
  local code=$1 text=$2; shift 3
  set +e
  if [ -n "$run_path" ]; then env PATH="$run_path" "$shadowlab" "$@" >"$tmp/out.txt" 2>"$tmp/err.txt"
  else "$shadowlab" "$@" >"$tmp/out.txt" 2>"$tmp/err.txt"; fi
  local got=$?
  set -e
  [ "$got" = "$code" ] || { cat "$tmp/err.txt"; fail "exit $got, expected $code: $*"; }
  grep -qF -- "$text" "$tmp/err.txt" || { cat "$tmp/err.txt"; fail "no '$text' in stderr of: $*"; }
}

# Presenter mode: the same tour step with --presenter and with --hide-ui (the view alone).
common=(--backend osmesa --tour shadow-mapping --tour-step 2 --frames 4 --size 960x540 --quiet)
"$shadowlab" "${common[@]}" --presenter --screenshot presenter.png
"$shadowlab" "${common[@]}" --hide-ui --screenshot plain.png
"$shadowlab" "${common[@]}" --screenshot panel.png
"$python" - <<'PY'
import numpy as np
from PIL import Image
load = lambda f: np.asarray(Image.open(f).convert('RGB')).astype(int)
presenter, plain, panel = load('presenter.png'), load('plain.png'), load('panel.png')
assert presenter.shape == (540, 960, 3), presenter.shape
# No panel: the top of the left part is the scene, as in the slide without the UI, not the panel.
top_left = (slice(0, 200), slice(0, 300))
assert np.abs(presenter[top_left] - plain[top_left]).mean() < 2, 'presenter mode shows the panel'
assert np.abs(panel[top_left] - plain[top_left]).mean() > 10, 'the check cannot tell the panel from the scene'
# The caption box: over the bottom left (2% .. 62% of the width), dark with light text; the
# figures box at the bottom right. The plain slide has neither.
def box(image, cols):
    region = image[int(0.88 * 540):int(0.96 * 540), cols]
    dark = (region.max(axis=2) < 80).mean()
    text = (region.min(axis=2) > 200).mean()
    return dark, text
for name, cols in (('caption', slice(30, 560)), ('figures', slice(640, 940))):
    dark, text = box(presenter, cols)
    plain_dark, _ = box(plain, cols)
    assert dark > 0.5 and text > 0.02, f'no {name} box (dark {dark:.2f}, text {text:.3f})'
    assert plain_dark < 0.2, f'the plain slide has a dark {name} region ({plain_dark:.2f}): the check cannot fail'
# The caption is large: its text rows come in lines taller than the panel's 15 px font.
region = presenter[int(0.5 * 540):int(0.97 * 540), 30:560]
rows = (region.min(axis=2) > 200).sum(axis=1) > 0
runs, run = [], 0
for r in rows:
    if r: run += 1
    elif run: runs.append(run); run = 0
assert runs and max(runs) >= 18, f'caption lines {runs}: the presenter font is not large'
print('ok: presenter slide, caption and figures boxes, caption lines', max(runs), 'px high')
PY

# A grid of three or four techniques.
r=(render --backend osmesa --scene cube --size 640x360 --frames 2 --quiet)
"$shadowlab" "${r[@]}" --compare shadowmap,shadowmap,shadowmap,shadowmap --out same4.png
"$shadowlab" "${r[@]}" --compare shadowmap,pcf,pcss,vsm --out grid4.png
"$shadowlab" "${r[@]}" --compare shadowmap,pcf,pcss --out grid3.png
expect 2 "--compare 'shadowmap,pcf,pcss,vsm,esm': expected A,B" -- render --backend osmesa --scene cube --compare shadowmap,pcf,pcss,vsm,esm --out x.png
expect 2 "--compare-layout wipe: compares two techniques" -- --backend osmesa --scene cube --frames 2 --compare pcf,pcss --compare-layout wipe
expect 2 "at most three techniques beside --technique" -- --backend osmesa --scene cube --frames 2 --compare pcf,pcss,vsm,esm
"$python" - <<'PY'
import numpy as np
from PIL import Image
load = lambda f: np.asarray(Image.open(f).convert('RGB')).astype(int)
def quarters(image):
    h, w = image.shape[0] // 2, image.shape[1] // 2
    # The upper 60% of each quarter: the cube and its shadow, above the label.
    return [image[y + 4:y + int(0.6 * h), x + 4:x + w - 4] for y in (0, h) for x in (0, w)]   # off the dividing lines
same, four, three = load('same4.png'), load('grid4.png'), load('grid3.png')
q = quarters(same)
for i in range(1, 4):
    d = np.abs(q[0] - q[i]).mean()
    assert d < 1.0, f'quarter {i} of the same technique differs from A by {d:.2f}: the quarters do not share the view'
q = quarters(four)
edge = [int((np.abs(q[0] - q[i]).max(axis=2) > 20).sum()) for i in (1, 2, 3)]
assert min(edge) > 10, f'pixels of B, C, D over 20 levels from A: {edge}: the grid did not draw four techniques'
# Each quarter's label: a dark box in its lower left corner.
h, w = four.shape[0] // 2, four.shape[1] // 2
for i, (y, x) in enumerate(((0, 0), (0, w), (h, 0), (h, w))):
    label = four[y + h - 30:y + h - 8, x + 10:x + 120]
    assert (label.max(axis=2) < 60).mean() > 0.4, f'no label in quarter {"ABCD"[i]}'
# Three techniques: the fourth quarter is empty (the window's background).
empty = three[h + 10:2 * h - 10, w + 10:2 * w - 10]
assert np.abs(empty - empty[0, 0]).max() < 3 and empty.mean() < 40, 'the empty quarter of a grid of three is drawn'
print('ok: grid of four (equal quarters for one technique, four labels), grid of three with an empty quarter')
PY

# A path played outside a tour, as the panel's "Camera and light paths" plays one, at a speed: at
# 2 path frames a window frame, window frame 4 shows path frame 8.
cat > slide.json <<'JSON'
{"frames": 10, "keyframes": [
  {"time": 0, "camera": {"position": [3, 2, 4], "target": [0, 0.4, 0]}},
  {"time": 1, "camera": {"position": [0.6, 2, 4], "target": [-2.4, 0.4, 0]}}]}
JSON
p=(--backend osmesa --scene cube -t shadowmap --play-path slide.json --size 320x180 --hide-ui --quiet)
"$shadowlab" "${p[@]}" --path-speed 2 --frames 5 --screenshot speed2.png
"$shadowlab" "${p[@]}" --frames 9 --screenshot frame8.png
"$shadowlab" "${p[@]}" --frames 5 --screenshot frame4.png
expect 2 "path 'nowhere'" -- --backend osmesa --scene cube --frames 2 --play-path nowhere
"$python" - <<'PY'
import numpy as np
from PIL import Image
load = lambda f: np.asarray(Image.open(f).convert('RGB')).astype(int)
fast, eight, four = load('speed2.png'), load('frame8.png'), load('frame4.png')
same, other = np.abs(fast - eight).mean(), np.abs(fast - four).mean()
assert same < 0.5 and other > 2, f'speed 2 at window frame 4: {same:.2f} from path frame 8, {other:.2f} from path frame 4'
print(f'ok: a path at speed 2 shows path frame 8 at window frame 4 ({same:.2f} levels off, {other:.2f} from frame 4)')
PY

# Legends of the debug views (rendered through the window's overlays).
v=(render --backend osmesa --size 640x360 --frames 2 --quiet)
"$shadowlab" "${v[@]}" -t shadowmap --set fit=scene --scene forest-002 --view footprint --out footprint.png
"$shadowlab" "${v[@]}" -t csm --scene forest-002 --view coverage --out coverage.png
"$shadowlab" "${v[@]}" -t shadowmap --set fit=scene --scene pillars --view focus-body --out body-scene.png
"$shadowlab" "${v[@]}" -t shadowmap --set fit=focus-body --scene pillars --view focus-body --out body-fit.png
"$shadowlab" "${v[@]}" -t shadowmap --set resolution=256 --scene cube --view texel-grid --out grid.png
"$python" - <<'PY'
import numpy as np
from PIL import Image
load = lambda f: np.asarray(Image.open(f).convert('RGB')).astype(int)
def near(image, colour, tolerance=4):
    return int((np.abs(image - np.array(colour)).max(axis=2) <= tolerance).sum())
corner = (slice(0, 130), slice(160, 640))   # the legend's box, top right
fp = load('footprint.png')[corner]
blue = ((fp[..., 2] > 180) & (fp[..., 0] < 90)).sum()
red = ((fp[..., 0] > 200) & (fp[..., 1] < 70) & (fp[..., 2] < 60)).sum()
assert blue > 40 and red > 40, f'no log2 colour bar in the footprint legend (blue {blue}, red {red} pixels)'
cov = load('coverage.png')[corner]
swatches = [near(cov, c) for c in ((229, 51, 51), (51, 204, 51), (63, 102, 255), (242, 204, 25))]
assert min(swatches) > 40, f'coverage legend: pixels of each cascade colour {swatches}'
amber = near(load('body-scene.png')[corner], (255, 190, 60))
amber_fit = near(load('body-fit.png')[corner], (255, 190, 60))
assert amber > 40 and amber_fit < 5, f'focus-body without B says so ({amber} amber pixels), with B not ({amber_fit})'
grid = load('grid.png')[140:360]   # the ground in front of the cube and behind it
yellow = (grid[..., 0] > 180) & (grid[..., 1] > 150) & (grid[..., 2] < 110)
cyan = (grid[..., 2] > 180) & (grid[..., 1] > 150) & (grid[..., 0] < 120)
for band in range(0, grid.shape[0] - 20, 20):
    covered = (yellow | cyan)[band:band + 20].mean()
    assert covered < 0.35, f'texel grid rows {140 + band}..: {covered:.0%} lines, a wash'
assert yellow.sum() > 200 and cyan.sum() > 200, f'texel grid: yellow {yellow.sum()} and cyan {cyan.sum()} pixels'
print(f'ok: legends (footprint bar, {swatches} cascade swatch pixels, focus-body note), texel grid without a wash')
PY
# The shadow map's debug image at its own (square) aspect ratio between bars, its depths stretched
# from the nearest the map holds (black) to the farthest; the kernel view's magnified inset.
"$shadowlab" "${v[@]}" -t shadowmap --scene cube --view "shadow map" --out shadow-map.png
# (3 x 3 taps of a 2048-texel map: a few pixels on screen, which the inset shows 9 times larger)
"$shadowlab" "${v[@]}" -t pcf --set kernel=3 --set offset_scale=1 --set hardware_filter=0 --scene cube \
  --view kernel --probe 320,300 --out inset.png > inset.txt
"$python" - <<'PY'
import numpy as np
from PIL import Image
load = lambda f: np.asarray(Image.open(f).convert('RGB')).astype(int)
image = load('shadow-map.png')
bars = np.concatenate([image[140:, :130], image[140:, 510:]], axis=1)   # below the legend
assert np.abs(bars - bars[0, 0]).max() <= 2, 'no plain bars beside the map: it is stretched to the view'
square = image[100:, 140:500, 1]   # below the legend's box
assert square.min() <= 3, f'the nearest depth is not black ({square.min()}): the range is not stretched (it was 11 before)'
inset = load('inset.png')
yellow = (np.abs(inset - np.array([255, 217, 0])).max(axis=2) <= 8)
near, corner = yellow[260:340, 280:360].sum(), yellow[0:200, 380:].sum()
assert near > 2 and corner > 10 * near, f'the inset does not magnify the box ({corner} yellow pixels in it, {near} at the probe)'
print(f'ok: shadow map square between bars, black at the nearest depth; kernel inset {corner} px against {near}')
PY
# The kernel view without --probe probes a shadow edge; the README's example probe is in a penumbra.
"$shadowlab" "${v[@]}" -t pcss --scene contact --view kernel --out kernel-auto.png > auto.txt
readme=$(grep -o 'render --scene contact --technique pcss [^#]*--view kernel [^#]*' "$source_dir/README.md" | head -1)
[ -n "$readme" ] || fail "no kernel example in the README"
# shellcheck disable=SC2086
"$shadowlab" $readme --backend osmesa --quiet > readme.txt
"$python" - <<'PY'
import re
for name in ('auto.txt', 'readme.txt'):
    line = [l for l in open(name) if 'kernel=' in l][0]
    lit = float(re.search(r'lit=([0-9.]+)', line).group(1))
    assert 0.05 < lit < 0.95 and 'decision=searched' in line, f'{name}: not a penumbra or edge pixel: {line}'
    print(f'ok: {name}: lit {lit}')
PY

# --export refused before anything is drawn.
expect 2 "--export o.avi: expected a .gif, .mp4 or .webm" -- render --backend osmesa --scene cube --path orbit --export o.avi
expect 2 "--export o.gif: exports a path" -- render --backend osmesa --scene cube --export o.gif
expect 2 "--out: required" -- render --backend osmesa --scene cube
mkdir -p nobin
expect_noffmpeg() { run_path="$tmp/nobin"; expect "$@"; run_path=""; }
expect_noffmpeg 2 "--export o.gif: needs the ffmpeg program" -- render --backend osmesa --scene cube --path orbit --export o.gif
expect_noffmpeg 2 "--export w.mp4: needs the ffmpeg program" -- --backend osmesa --scene cube --frames 3 --export w.mp4
expect 2 "--export w.gif: records the frames of a run of --frames N" -- --backend osmesa --scene cube --smoke-test 3 --export w.gif
[ ! -e o.gif ] && [ ! -e w.mp4 ] || fail "a refused export wrote a file"

if ! command -v ffmpeg >/dev/null; then
  echo "SKIP: the export checks need the ffmpeg program (Debian package ffmpeg, in tools/setup.sh)"
  exit 0
fi
"$shadowlab" render --backend osmesa --scene cube -t shadowmap --path sweep --path-frames 12 --size 320x180 --export sweep.gif --quiet
"$shadowlab" render --backend osmesa --scene cube -t shadowmap --path sweep --path-frames 10 --size 320x180 --export sweep.mp4 --quiet
# A session saved on a path (written as the window writes one) plays its path again; --export
# records the window's frames, the view only: 320 px less the panel's 144 (45%).
cat > session.json <<'JSON'
{"title": "session: shadowmap on cube", "scene": "cube", "technique": "shadowmap",
 "camera": {"position": [3.0, 2.0, 4.0], "target": [0.0, 0.4, 0.0], "fov": 45.0},
 "path": "sweep", "pathFrames": 12, "caption": "Saved on a path."}
JSON
"$shadowlab" --backend osmesa --session session.json --frames 6 --size 320x180 --export window.gif --quiet
frames_mp4=$(ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames -of csv=p=0 sweep.mp4)
[ "$frames_mp4" = 10 ] || fail "sweep.mp4 holds $frames_mp4 frames, expected 10"
"$python" - <<'PY'
import numpy as np
from PIL import Image, ImageSequence
for name, count, size in (('sweep.gif', 12, (320, 180)), ('window.gif', 6, (176, 180))):
    image = Image.open(name)
    frames = [np.asarray(f.convert('RGB')).astype(int) for f in ImageSequence.Iterator(image)]
    assert len(frames) == count, f'{name}: {len(frames)} frames, expected {count}'
    assert image.size == size, (name, image.size)
    moved = np.abs(frames[0] - frames[len(frames) // 2]).mean()
    assert moved > 2, f'{name}: the first and middle frames are the same ({moved:.2f}): the path did not play'
    print(f'ok: {name}, {count} frames at {size}, first and middle {moved:.1f} levels apart')
PY
echo "ok: sweep.mp4, $frames_mp4 frames"
