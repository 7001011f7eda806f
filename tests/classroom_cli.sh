#!/usr/bin/env bash
# The classroom window without a display (issue 14), on OSMesa:
#   - `--frames N --screenshot slide.png` draws the window offscreen, panel included, and writes
#     the slide (it used to ignore the flags and run the whole report);
#   - window options that cannot work without a display, and --screenshot without --frames,
#     exit 2 naming the option;
#   - `render --compare A,B` writes the comparison headless with both labels, each half framing
#     the whole scene (the same technique on both sides gives two equal halves: the old split
#     showed two different halves of one frame);
#   - `render --compare A,reference` (the ground truth as B) and the wipe and difference layouts.
set -euo pipefail
shadowlab=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
unset DISPLAY WAYLAND_DISPLAY
python=/usr/bin/python3   # Debian's, with python3-pil (a dependency of python3-matplotlib)
cd "$tmp"

fail() { echo "FAIL: $*"; exit 1; }

# expect CODE TEXT -- ARGS: exit code CODE and TEXT in stderr.
expect() {
  local code=$1 text=$2; shift 3
  set +e
  "$shadowlab" "$@" >"$tmp/out.txt" 2>"$tmp/err.txt"
  local got=$?
  set -e
  [ "$got" = "$code" ] || { cat "$tmp/err.txt"; fail "exit $got, expected $code: $*"; }
  grep -qF -- "$text" "$tmp/err.txt" || { cat "$tmp/err.txt"; fail "no '$text' in stderr of: $*"; }
}

# A slide from a machine without a display: the window with its panel, offscreen.
"$shadowlab" --backend osmesa -t pcss --scene contact --frames 30 --size 800x450 --screenshot slide.png --quiet
[ -s slide.png ] || fail "no slide.png"
[ ! -d out ] || fail "the report ran (out/ exists) instead of the window"
"$python" - slide.png <<'PY'
import sys
import numpy as np
from PIL import Image
image = np.asarray(Image.open(sys.argv[1]).convert('RGB')).astype(int)
assert image.shape == (450, 800, 3), image.shape
panel_width = 360   # panelWidthFor(1.0, 800): the panel on the left, the view beside it
panel, view = image[:, :panel_width - 4], image[:, panel_width + 4:]
# The panel: ImGui's dark window with text (many light pixels on a dark background).
assert (panel.max(axis=2) > 180).mean() > 0.01, 'no panel text'
# The view: the lit scene, many colours, and not the panel's background.
colours = len({tuple(p) for p in view[::7, ::7].reshape(-1, 3)})
assert colours > 20, f'view has only {colours} colours'
# Scene pixels (not the panel's dark grey) in the right part: the lit ground of contact.
assert (view.mean(axis=2) > 150).mean() > 0.2, 'no lit scene beside the panel'
print(f'ok: slide 800x450, panel text and a view of {colours}+ colours')
PY

# Side by side with --measure (the "Measure accuracy" button): each side measured for its own
# technique. `none` has no shadows, so its error is far larger than shadowmap's; the old code
# measured the right-hand technique and labelled it with the left-hand one.
"$shadowlab" --backend osmesa -t none --compare shadowmap --scene contact --size 640x360 --frames 10 --measure \
  --screenshot measured.png 2>measure.log
grep -q "accuracy of none" measure.log || { cat measure.log; fail "no measurement of none"; }
grep -q "accuracy of shadowmap" measure.log || { cat measure.log; fail "no measurement of shadowmap"; }
none_mae=$(sed -n 's/.*accuracy of none.*: MAE \([0-9.]*\).*/\1/p' measure.log)
shadowmap_mae=$(sed -n 's/.*accuracy of shadowmap.*: MAE \([0-9.]*\).*/\1/p' measure.log)
"$python" -c "import sys; n, s = float('$none_mae'), float('$shadowmap_mae'); sys.exit(0 if n > 0.002 and n > 5 * s else 1)" ||
  fail "none MAE $none_mae should be well above shadowmap MAE $shadowmap_mae"
# And each side's memory is its own: none has none, a shadow map has some.
grep -q "accuracy of none: .* 0.00 MiB" measure.log || { cat measure.log; fail "none's memory is not 0"; }
grep "accuracy of shadowmap" measure.log | grep -qv " 0.00 MiB" || { cat measure.log; fail "shadowmap's memory is 0"; }

# Options the window alone reads, with neither a display nor --frames: exit 2, naming them.
expect 2 "--compare: no display" -- --backend osmesa --compare pcf
expect 2 "--screenshot x.png: needs --frames" -- --backend osmesa --screenshot x.png
expect 2 "--compare-layout 'diagonal'" -- --backend osmesa --frames 2 --compare pcf --compare-layout diagonal
expect 2 "--compare 'nosuch'" -- --backend osmesa --frames 2 --compare nosuch
expect 2 "--measure-reference: no display" -- --backend osmesa --measure-reference soft
expect 2 "--measure-reference 'fuzzy': expected auto, hard or soft" -- --backend osmesa --frames 2 --measure --measure-reference fuzzy
expect 2 "--measure-samples: Value 1000 not in range 4 to 256" -- --backend osmesa --frames 2 --measure --measure-samples 1000
expect 2 "--compare 'pcss,'" -- render --backend osmesa --compare pcss, --out x.png
expect 2 "no such technique" -- render --backend osmesa --compare pcss,nosuch --out x.png

# Side by side of one technique with itself: the halves are equal (same camera, same framing).
"$shadowlab" render --backend osmesa --scene dragon-like --size 640x360 --compare shadowmap,shadowmap --out same.png --quiet
"$shadowlab" render --backend osmesa --scene dragon-like --size 640x360 --compare shadowmap,pcss --out pair.png --quiet
"$shadowlab" render --backend osmesa --scene dragon-like --size 640x360 --compare shadowmap,pcss --compare-layout wipe \
  --wipe 0.3 --out wipe.png --quiet
"$shadowlab" render --backend osmesa --scene dragon-like --size 640x360 --compare shadowmap,pcss --compare-layout difference \
  --out difference.png --quiet
"$shadowlab" render --backend osmesa --scene contact --size 320x180 --frames 1 --compare pcss,reference --out truth.png --quiet
"$python" - <<'PY'
import numpy as np
from PIL import Image
def load(name):
    return np.asarray(Image.open(name).convert('RGB')).astype(int)
same, pair = load('same.png'), load('pair.png')
assert same.shape == (360, 640, 3), same.shape
rows = slice(0, 300)   # above the labels
left, right = same[rows, 4:316], same[rows, 324:636]
diff = np.abs(left - right).max()
assert diff <= 2, f'the halves of shadowmap,shadowmap differ by {diff}: not the same framing'
assert len({tuple(p) for p in left[::5, ::5].reshape(-1, 3)}) > 30, 'blank half'
# Labels: white text on a dark box at the bottom of each half.
for half in (same[300:, :320], same[300:, 320:]):
    assert (half.min(axis=2) > 230).sum() > 30, 'no label text'
# Two different techniques: the halves differ (the soft shadow of pcss), each still a full view.
assert np.abs(pair[rows, 4:316] - pair[rows, 324:636]).mean() > 0.2, 'shadowmap and pcss halves identical'
wipe, difference, truth = load('wipe.png'), load('difference.png'), load('truth.png')
assert wipe.shape == (360, 640, 3) and difference.shape == (360, 640, 3) and truth.shape == (180, 320, 3)
# The difference view: orange or blue where the shadow terms differ, dark grey elsewhere.
hue = (np.abs(difference[..., 0] - difference[..., 2]) > 60).mean()
assert 0.0005 < hue < 0.5, f'difference view: {hue:.4f} of pixels coloured'
print('ok: side by side equal for one technique, labels, wipe, difference and reference images')
PY
# Issue 29: without --measure-reference the window judges each technique against its own kind of
# reference, as the tour pages: PCSS against eval's soft figure, shadow mapping against the hard one.
for pair in pcss:soft shadowmap:hard; do
  technique=${pair%:*} kind=${pair#*:}
  "$shadowlab" --backend osmesa --size 320x180 --hide-ui -t "$technique" --scene contact --frames 6 --measure \
    --measure-samples 64 --screenshot "own-$technique.png" 2>"own-$technique.log" || { cat "own-$technique.log"; fail "window $technique"; }
  "$shadowlab" eval --backend osmesa -t "$technique" --scene contact --size 320x180 --frames 3 --reference both \
    --samples 64 --reference-adaptive off --json >"own-$technique.json" 2>/dev/null || fail "eval $technique"
  "$python" - "own-$technique.log" "own-$technique.json" "$technique" "$kind" <<'PY'
import json, re, sys
log, figures, technique, kind = open(sys.argv[1]).read(), json.load(open(sys.argv[2]))['accuracy'], sys.argv[3], sys.argv[4]
mae = re.findall(rf'accuracy of {technique} [^:]*: MAE ([0-9.]+)', log)
assert len(mae) == 1, f'one measurement expected:\n{log}'
other = 'hard' if kind == 'soft' else 'soft'
expected, wrong = figures[kind]['mae'], figures[other]['mae']
assert abs(float(mae[0]) - expected) <= 2e-6 + 1e-3 * expected, f'{technique}: window MAE {mae[0]}, eval {kind} {expected}'
assert abs(expected - wrong) > 1e-5, f'{technique}: hard and soft figures too close to tell ({expected}, {wrong})'
print(f'ok: {technique} measured against the {kind} reference by default: {mae[0]} ({other}: {wrong:.6f})')
PY
done

echo "classroom_cli: all passed"
