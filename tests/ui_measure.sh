#!/usr/bin/env bash
# "Measure accuracy" in the real window under Xvfb (issue 32): the reference is traced on a worker
# while the frame loop keeps presenting frames, and the figures are eval's for the same frame.
#  1. A scripted window (--frames with --measure, soft reference of 64 rays, UI hidden so the view
#     is the whole 640x360 window): the log says how many frames were presented between the
#     start of the measurement and its result (at least 5), and the MAE it logs is `eval`'s on the
#     same scene, technique and size (uniform soft reference of 64 rays, the same seed).
#  2. Driven by xdotool: M starts a measurement (soft, 256 rays: seconds on this machine), Right
#     goes to the tour's next step, in another scene, which cancels it; M again, then Escape
#     quits while it runs: the worker is joined and the app exits with 0.
set -euo pipefail
if [ "${1:-}" != --inside ]; then
  exec "$1" -a -s "-screen 0 1280x800x24 -noreset" bash "$0" --inside "$2"
fi
shadowlab=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
for _ in $(seq 50); do xdotool getmouselocation >/dev/null 2>&1 && break; sleep 0.2; done   # the server answers

# 1. Frames presented during the measurement, and its figure against eval's.
"$shadowlab" --backend glfw --size 640x360 --hide-ui -t pcss --scene contact --frames 12 --measure \
  --measure-reference soft --measure-samples 64 --screenshot measured.png 2>window.log ||
  { cat window.log; echo "FAIL: the window run failed"; exit 1; }
"$shadowlab" eval --backend osmesa -t pcss --scene contact --size 640x360 --frames 3 --reference soft --samples 64 \
  --reference-adaptive off --json >eval.json 2>eval.log || { cat eval.log; echo "FAIL: eval failed"; exit 1; }
/usr/bin/python3 - window.log eval.json <<'PY'
import json, re, sys
log = open(sys.argv[1]).read()
started = re.findall(r'measuring accuracy on a worker thread from presented frame (\d+)', log)
done = re.findall(r'accuracy measured in ([0-9.]+) s on a worker thread: (\d+) frames presented meanwhile, '
                  r'at most (\d+) ms apart', log)
mae = re.findall(r'accuracy of pcss [^:]*: MAE ([0-9.]+)', log)
assert len(started) == 1 and len(done) == 1 and len(mae) == 1, f'expected one measurement in the log:\n{log}'
seconds, frames, gap = float(done[0][0]), int(done[0][1]), int(done[0][2])
assert frames >= 5, f'only {frames} frames presented in the {seconds} s the measurement took: the loop stalled\n{log}'
assert gap <= 500 * seconds, f'a frame took {gap} ms of the {seconds} s measurement: the loop stalled\n{log}'
expected = json.load(open(sys.argv[2]))['accuracy']['soft']['mae']
assert abs(float(mae[0]) - expected) <= 2e-6 + 1e-3 * expected, f'window MAE {mae[0]}, eval {expected}'
print(f'ok: {frames} frames presented during the {seconds} s measurement, at most {gap} ms apart; '
      f'MAE {mae[0]} (eval {expected:.6f})')
PY

# 2. Cancelled by a scene change (a tour step) and by quitting.
cat > tour.json <<'JSON'
{"title": "measure", "description": "two scenes",
 "steps": [{"title": "contact", "scene": "contact", "technique": "pcss", "caption": "one"},
           {"title": "cube", "scene": "cube", "technique": "pcf", "caption": "two"}]}
JSON
"$shadowlab" --backend glfw --size 960x540 --tour tour.json --measure-reference soft --measure-samples 256 2>app.log &
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
count() { grep -c "$1" app.log || true; }
await() {   # PATTERN N: until the log has N lines matching
  for _ in $(seq 300); do [ "$(count "$1")" -ge "$2" ] && return 0; sleep 0.1; done
  cat app.log; echo "FAIL: no '$1' (#$2) in the log"; kill $app; exit 1
}
xdotool key m
await "measuring accuracy on a worker thread" 1
xdotool key Right
await "tour step 2 of 2" 1
xdotool key m
await "measuring accuracy on a worker thread" 2
xdotool key Escape
for _ in $(seq 100); do kill -0 $app 2>/dev/null || break; sleep 0.1; done
if kill -0 $app 2>/dev/null; then cat app.log; echo "FAIL: Escape did not quit within 10 s while measuring"; kill $app; exit 1; fi
wait $app || { cat app.log; echo "FAIL: exit status $?"; exit 1; }
# A trace faster than the key (a machine with many cores) may have finished first: then it was not cancelled.
finished=$(count "accuracy measured in")
cancelled_step=$(count "measurement cancelled: a tour step was applied")
cancelled_quit=$(count "measurement cancelled: the window closed")
[ $((finished + cancelled_step + cancelled_quit)) = 2 ] || { cat app.log; echo "FAIL: two measurements started, $finished finished, $((cancelled_step + cancelled_quit)) cancelled"; exit 1; }
[ "$finished" = 2 ] && echo "note: both traces finished before the keys: nothing was cancelled on this machine"
grep -q "accuracy of pcf" app.log && [ "$cancelled_quit" = 1 ] && { cat app.log; echo "FAIL: a cancelled measurement reported figures"; exit 1; }
echo "ok: measurements cancelled by the tour step ($cancelled_step) and by quitting ($cancelled_quit); exit 0"
