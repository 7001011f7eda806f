#!/usr/bin/env bash
# The window a lecturer uses, without a display (issue 29), on OSMesa:
#   - presenter mode drawn offscreen: no panel, the tour step's caption in a large box over the
#     bottom of the view and the figures box beside it (absent from the same slide without it);
#   - `render --path P --export FILE.gif|.mp4` and the window's `--export` with --frames (a session
#     saved on a path, played again): the frames counted in the encoded file, and they move;
#   - --export refused with exit 2 naming the option: no ffmpeg on PATH, a format it does not
#     know, without --path (render) or without --frames (window).
set -euo pipefail
shadowlab=$1
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
