#!/usr/bin/env bash
# The window a lecturer uses, in the real window under Xvfb (issue 29), driven by xdotool:
#   1. presenter mode (--presenter): the window takes the whole 1280x800 screen, no panel; `?`
#      opens the help overlay over the view; P leaves presenter mode: the window is 960x540
#      again with its panel;
#   2. dragging the wipe's handle leaves the camera where it was (a session saved before and
#      after the drag holds the same camera); dragging the view up by whole screens orbits the
#      eye down, but never under the ground of `contact` (y = 0; the saved camera says where);
#   3. scrolled down the panel, Right to the next step brings the panel back to the caption: its
#      top looks as when the window starts on that step.
set -euo pipefail
if [ "${1:-}" != --inside ]; then
  exec "$1" -a -s "-screen 0 1280x800x24 -noreset" bash "$0" --inside "$2"
fi
shadowlab=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
fail() { echo "FAIL: $*"; [ -f app.log ] && tail -20 app.log; exit 1; }

for _ in $(seq 50); do xdotool getmouselocation >/dev/null 2>&1 && break; sleep 0.2; done   # the server answers
# start ARGS...: the window in the background ($app, $window), its log in app.log.
start() {
  rm -f app.log
  "$shadowlab" --backend glfw --size 960x540 "$@" 2>app.log &
  app=$!
  window=""
  for _ in $(seq 150); do
    window=$(xdotool search --name "^shadowlab$" 2>/dev/null | head -1 || true)
    [ -n "$window" ] && break
    sleep 0.2
  done
  [ -n "$window" ] || fail "no window"
  sleep 3
  xdotool windowfocus --sync "$window" 2>/dev/null || true
}
# wait_log PATTERN COUNT: until app.log holds COUNT lines matching PATTERN.
wait_log() {
  for _ in $(seq 300); do [ "$(grep -c -- "$1" app.log || true)" -ge "$2" ] && return 0; sleep 0.2; done
  fail "waited for $2 lines of '$1'"
}
shot() { local n; n=$(grep -c "screenshot saved" app.log || true); xdotool key F12; wait_log "screenshot saved" $((n + 1)); }
quit() {
  xdotool key Escape
  for _ in $(seq 150); do kill -0 $app 2>/dev/null || break; sleep 0.2; done
  kill -0 $app 2>/dev/null && { kill $app; fail "Escape did not quit"; }
  wait $app || fail "exit status $?"
}
saved() { sed -n "s/.*$1: \(.*\)/\1/p" app.log; }

# 1. Presenter mode and the help overlay.
start --tour shadow-mapping --presenter --screenshot-dir shots1
wait_log "presenter mode: full screen" 1
sleep 2
shot
xdotool key question; sleep 1.5
shot
xdotool key p
wait_log "presenter mode ended" 1
sleep 2
shot
quit
saved "screenshot saved" > shots1.txt
/usr/bin/python3 - <<'PY'
import numpy as np
from PIL import Image
files = open('shots1.txt').read().split()
assert len(files) == 3, files
full, help_, windowed = (np.asarray(Image.open(f).convert('RGB')).astype(int) for f in files)
assert full.shape == (800, 1280, 3), f'presenter mode is not full screen: {full.shape}'
assert windowed.shape == (540, 960, 3), f'P did not give the window back: {windowed.shape}'
# The panel is dark; presenter mode shows the scene's sky there instead.
assert full[0:150, 0:300].mean() > 70, f'presenter mode shows the panel (mean {full[0:150, 0:300].mean():.0f})'
assert windowed[0:150, 0:300].mean() < 50, f'the panel is not back after P (mean {windowed[0:150, 0:300].mean():.0f})'
# The help overlay in the middle of the view.
middle = (slice(250, 550), slice(400, 880))
assert np.abs(help_[middle] - full[middle]).mean() > 15, '? drew no overlay'
print('ok: presenter mode full screen without the panel, ? overlay, P back to 960x540 with the panel')
PY

# 2. The wipe's drag keeps the camera; orbiting stays above the ground. 960x540, 360 px panel:
# the divider starts at x 660 with its handle at mid-height.
start -t shadowmap --compare pcss --compare-layout wipe --scene contact --session-dir sessions2
xdotool key F5; wait_log "session saved" 1
xdotool mousemove --window "$window" 660 270; sleep 1
# Pressed and moved at once, as a quick hand does: the frame that sees the press also sees the
# motion (the camera used to orbit by it before the overlay knew a drag had begun).
xdotool mousedown 1 mousemove --window "$window" 700 270 mousemove --window "$window" 760 270; sleep 0.5
for x in 820 860; do xdotool mousemove --window "$window" $x 270; sleep 0.5; done
sleep 1; xdotool mouseup 1; sleep 1
xdotool key F5; wait_log "session saved" 2
for _ in 1 2 3; do   # drag the view upwards by most of its height, three times
  xdotool mousemove --window "$window" 500 520; sleep 0.5
  xdotool mousedown 1; sleep 0.5
  for y in 420 320 220 120 20; do xdotool mousemove --window "$window" 500 $y; sleep 0.4; done
  xdotool mouseup 1; sleep 0.5
done
sleep 1
xdotool key F5; wait_log "session saved" 3
quit
saved "session saved" > sessions2.txt
/usr/bin/python3 - <<'PY'
import json
before, after_wipe, after_orbit = (json.load(open(f)) for f in open('sessions2.txt').read().split())
moved = max(abs(a - b) for a, b in zip(before['camera']['position'], after_wipe['camera']['position']))
assert moved < 1e-4, f'dragging the wipe moved the camera by {moved}'
assert after_wipe['wipe'] > 0.75, f'the wipe was not dragged ({after_wipe["wipe"]})'
eye = after_orbit['camera']['position']
assert max(abs(a - b) for a, b in zip(eye, before['camera']['position'])) > 1.0, 'the drags did not orbit the camera'
assert eye[1] > 0.0, f'the orbit took the eye under the ground: {eye}'
print(f'ok: wipe dragged to {after_wipe["wipe"]:.2f} with the camera still, orbit eye at y {eye[1]:.3f} above the ground')
PY

# 3. The panel scrolls back to the caption on a new step.
start --tour shadow-mapping --screenshot-dir shots3
wait_log "tour step 1 of" 1
xdotool mousemove --window "$window" 180 400; sleep 0.5
for _ in $(seq 40); do xdotool click 5; done
sleep 1.5
shot
xdotool key Right; wait_log "tour step 2 of" 1
sleep 1.5
shot
quit
saved "screenshot saved" > shots3.txt
start --tour shadow-mapping --tour-step 2 --screenshot-dir shots4
wait_log "tour step 2 of" 1
xdotool mousemove --window "$window" 180 400; sleep 1.5
shot
quit
saved "screenshot saved" >> shots3.txt
/usr/bin/python3 - <<'PY'
import numpy as np
from PIL import Image
scrolled, next_step, fresh = (np.asarray(Image.open(f).convert('RGB')).astype(int) for f in open('shots3.txt').read().split())
top = (slice(0, 260), slice(0, 340))   # the panel's top: the tour player and the caption
away = np.abs(scrolled[top] - fresh[top]).mean()
back = np.abs(next_step[top] - fresh[top]).mean()
assert away > 4, f'the wheel did not scroll the panel ({away:.2f})'
assert back < away / 3, f'the panel stayed scrolled after Right ({back:.2f} against {away:.2f} scrolled)'
print(f'ok: the panel back at the caption on the next step ({back:.2f} levels from a fresh start, {away:.2f} scrolled)')
PY
