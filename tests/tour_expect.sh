#!/usr/bin/env bash
# A tour step's "expect" (issue 29) through `shadowlab tour` on OSMesa: a deliberately wrong
# expectation makes the run exit 3 with a message naming the tour, the step, the expectation and
# the figure measured, and the page marks it FAILED beside the caption (the right one: passed);
# without it the same tour exits 0; a malformed one is exit 2 before anything is drawn.
#   tour_expect.sh SHADOWLAB
set -euo pipefail
shadowlab=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
unset DISPLAY WAYLAND_DISPLAY
cd "$tmp"
fail() { echo "FAIL: $*"; exit 1; }
run() { set +e; "$shadowlab" tour "$1" --backend osmesa --size 160x90 --frames 1 --warmup 1 --bench-frames 2 --samples 8 \
          --out "$2" --quiet >"$2.out" 2>"$2.err"; echo $? >"$2.rc"; set -e; }

# Step 2 (a 256-texel map: its error is well above the 2048 map's) claims both a right and a wrong thing.
write() {
  cat >"$1" <<JSON
{"title": "Checked", "steps": [
  {"title": "fine map", "scene": "cube", "technique": "shadowmap", "caption": "A 2048 map.", "expect": {"mae": "< 0.01"}},
  {"title": "coarse map", "scene": "cube", "technique": "shadowmap", "parameters": {"resolution": 256},
   "caption": "A 256 map.", "expect": {"mae": [$2]}}
]}
JSON
}
write wrong.json '"> previous", "< 0.5 * previous"'
run wrong.json wrong
[ "$(cat wrong.rc)" = 3 ] || { cat wrong.err; fail "a failed expectation: exit $(cat wrong.rc), expected 3"; }
grep -qF 'wrong.json: 1 of 3 expectations failed' wrong.err || { cat wrong.err; fail "no count of failures"; }
grep -qE 'wrong.json: steps\[1\] \("coarse map"\): expect mae < 0.5 \* previous: measured 0\.[0-9]+, bound' wrong.err ||
  { cat wrong.err; fail "the message does not name tour, step, expectation and figure"; }
[ -s wrong/index.html ] && [ -s wrong/step-02.png ] || fail "the pages were not written"
# The mark sits in the step's figure, after its caption; the right expectation is marked passed.
python3 - wrong/index.html wrong/README.md <<'PY'
import re, sys
page = open(sys.argv[1]).read()
step2 = page.split('<section id="step-2">')[1].split('</section>')[0]
figure = step2.split('<figure>')[1].split('</figure>')[0]
assert re.search(r'</figcaption>\s*<ul class="expect">', figure), 'the expectations are not beside the caption'
assert re.search(r'<li class="failed">FAILED: mae &lt; 0.5 \* previous: measured', figure), figure
assert re.search(r'<li class="passed">passed: mae &gt; previous', figure), figure
assert 'li.failed{color:#b00000' in page, 'a failure is not drawn in red'
step1 = page.split('<section id="step-1">')[1].split('</section>')[0]
assert 'class="failed"' not in step1 and 'passed: mae &lt; 0.01' in step1, step1
md = open(sys.argv[2]).read()
assert '**FAILED**: mae < 0.5 * previous' in md and 'passed: mae > previous' in md, md
PY

write right.json '"> previous"'
run right.json right
[ "$(cat right.rc)" = 0 ] || { cat right.err; fail "every expectation holds: exit $(cat right.rc), expected 0"; }
grep -qF '2 expectations passed' right.out || { cat right.out; fail "no count of passed expectations"; }
! grep -q 'class="failed"' right/index.html || fail "a passing tour shows a failure"

# Malformed: exit 2 naming file, step and key, before any frame (no folder written).
write bad.json '"about 0.01"'
run bad.json bad
[ "$(cat bad.rc)" = 2 ] || { cat bad.err; fail "a malformed expectation: exit $(cat bad.rc), expected 2"; }
grep -qF "bad.json: steps[1].expect.mae: 'about 0.01': expected a comparison" bad.err || { cat bad.err; fail "bad message"; }
[ ! -e bad/index.html ] || fail "a malformed tour was drawn"
echo "ok: a wrong expectation exits 3 and is marked on the page, a right one exits 0, a malformed one 2"
