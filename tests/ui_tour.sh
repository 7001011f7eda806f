#!/usr/bin/env bash
# The tour player in the real window under Xvfb (issue 14), driven by xdotool: `--tour
# shadow-mapping` starts at step 1; Right, Right, Left, Right, Home (restart), Page_Down go to
# steps 2, 3, 2, 3, 3 and 4, each applied by the same UiCommand the panel's buttons send (the
# log says which step); F5 saves a session under sessions/ that is a valid tour step holding
# step 4's parameters (bias 2 and 2, culling back faces), and the app exits with 0.
set -euo pipefail
if [ "${1:-}" != --inside ]; then
  exec "$1" -a -s "-screen 0 1280x800x24 -noreset" bash "$0" --inside "$2"
fi
shadowlab=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"

for _ in $(seq 50); do xdotool getmouselocation >/dev/null 2>&1 && break; sleep 0.2; done   # the server answers
"$shadowlab" --backend glfw --size 960x540 --tour shadow-mapping 2>app.log &
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
xdotool mousemove 900 300   # over the view, not the panel
# Each key waits for the app to show its effect (a new "tour step" line, or the saved session)
# before the next one: under ASan on a loaded machine a step's scene load takes seconds.
steps_logged() { grep -c "tour step [0-9]* of 9" app.log || true; }
for _ in $(seq 300); do [ "$(steps_logged)" -ge 1 ] && break; sleep 0.2; done
for key in Right Right Left Right Home Page_Down; do
  before=$(steps_logged)
  xdotool key "$key"
  for _ in $(seq 300); do [ "$(steps_logged)" -gt "$before" ] && break; sleep 0.2; done
done
xdotool key F5
for _ in $(seq 300); do ls sessions/*.json >/dev/null 2>&1 && break; sleep 0.2; done
xdotool key Escape
for _ in $(seq 300); do kill -0 $app 2>/dev/null || break; sleep 0.2; done
if kill -0 $app 2>/dev/null; then echo "FAIL: Escape did not quit"; kill $app; exit 1; fi
wait $app || { cat app.log; echo "FAIL: exit status $?"; exit 1; }

steps=$(sed -n 's/.*tour step \([0-9]*\) of 9.*/\1/p' app.log | tr '\n' ' ')
[ "$steps" = "1 2 3 2 3 3 4 " ] || { cat app.log; echo "FAIL: steps shown '$steps', expected '1 2 3 2 3 3 4 '"; exit 1; }
session=$(ls sessions/*.json 2>/dev/null | head -1 || true)
[ -n "$session" ] || { cat app.log; echo "FAIL: F5 saved no session"; exit 1; }
"$shadowlab" --backend osmesa --session "$session" --frames 2 --size 320x180 --screenshot restored.png --quiet
[ -s restored.png ] || { echo "FAIL: the saved session did not load"; exit 1; }
/usr/bin/python3 - "$session" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
assert s['scene'] == 'cube' and s['technique'] == 'shadowmap', s
p = s['parameters']
assert p['constant_bias'] == 2 and p['slope_bias'] == 2 and p['cull'] == 'back', p
assert {'camera', 'light', 'view', 'caption', 'title'} <= set(s), sorted(s)
print(f'ok: steps 1 2 3 2 3 3 4 by keys; session {sys.argv[1]} holds step 4 and loads')
PY
