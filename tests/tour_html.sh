#!/usr/bin/env bash
# `shadowlab tour` headless (issue 14), checked in a real browser: every built-in tour is drawn on
# OSMesa at a small size with a short benchmark, then its index.html is opened in headless
# Chromium. A copy of the page with a small script added (index.html itself has none) records,
# once the page has loaded, each image's naturalWidth; --dump-dom prints the DOM after it. Every
# image must have loaded (naturalWidth > 0, the PNG decoded) and every caption of the tour file
# must be on the page, in order. A copy with one image pointing at a missing file must fail the
# same check, so the check can tell. Every step's expectations must hold (exit 0) and be on the page.
#   tour_html.sh SHADOWLAB CHROMIUM
set -euo pipefail
shadowlab=$1
chromium=$2
source_dir=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
unset DISPLAY WAYLAND_DISPLAY
cd "$tmp"

# dump PAGE OUT: the DOM of PAGE after its load event, from a fresh profile, nothing fetched.
dump() {
  rm -rf "$tmp/profile"
  timeout 120 "$chromium" --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
    --disable-background-networking --disable-component-update --disable-sync --user-data-dir="$tmp/profile" \
    --window-size=1280,800 --virtual-time-budget=10000 --dump-dom "file://$1" >"$2" 2>"$tmp/chromium.log" ||
    { cat "$tmp/chromium.log"; echo "FAIL: chromium failed on $1"; exit 1; }
}

for tour in shadow-mapping soft-shadows large-scenes coloured-shadows; do
  start=$(date +%s)
  "$shadowlab" tour "$tour" --backend osmesa --size 256x144 --frames 2 --warmup 1 --bench-frames 3 --samples 16 \
    --out "$tmp/$tour" --quiet >"$tmp/$tour.log"
  # Exit 0 (set -e) means every step's "expect" held (issue 29: a failed one exits 3).
  echo "$tour: drawn in $(( $(date +%s) - start )) s; $(grep -o '[0-9]* expectations passed' "$tmp/$tour.log")"
  page="$tmp/$tour/index.html"
  ! grep -qi "<script" "$page" || { echo "FAIL: $page has a script"; exit 1; }
  # The checking copy: the page plus a load handler that writes what it found into the DOM.
  # It also records how wide the page is in a 1280-pixel window (issue 29: no sideways scrolling)
  # and the right edge of its widest table, image or list against the body's.
  sed 's#</body>#<script>window.addEventListener("load", () => { for (const i of document.images) i.dataset.naturalWidth = i.naturalWidth; const b = document.body; b.dataset.scrollWidth = document.documentElement.scrollWidth; b.dataset.widest = Math.max(...[...document.querySelectorAll("table,img,figure,dl,p")].map(e => e.getBoundingClientRect().right)); b.dataset.bodyRight = b.getBoundingClientRect().right; b.dataset.checked = "yes"; });</script></body>#' \
    "$page" >"$tmp/$tour/check.html"
  dump "$tmp/$tour/check.html" "$tmp/$tour/check.dom"
  # That the check can tell a missing image: shown once (the pages share their markup), which
  # saves three browser starts of the suite's longest test.
  if [ "$tour" = shadow-mapping ]; then
    sed '0,/src="step-01.png"/s//src="missing.png"/' "$tmp/$tour/check.html" >"$tmp/$tour/broken.html"
    dump "$tmp/$tour/broken.html" "$tmp/$tour/broken.dom"
  fi
  /usr/bin/python3 - "$source_dir/assets/tours/$tour.json" "$tmp/$tour" <<'PY'
import html.parser, json, os, re, sys
tour = json.load(open(sys.argv[1]))
folder = sys.argv[2]
captions = [' '.join(s['caption'].split()) for s in tour['steps']]

class Page(html.parser.HTMLParser):
    def __init__(self):
        super().__init__()
        self.images, self.captions, self.checked, self.inside = [], [], False, False
    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == 'img': self.images.append((a.get('src'), a.get('data-natural-width')))
        if tag == 'body':
            self.checked = a.get('data-checked') == 'yes'
            self.widths = {k: float(a.get('data-' + k, 'nan')) for k in ('scroll-width', 'widest', 'body-right')}
        if tag == 'figcaption': self.inside, self.text = True, ''
    def handle_endtag(self, tag):
        if tag == 'figcaption': self.inside = False; self.captions.append(' '.join(self.text.split()))
    def handle_data(self, data):
        if self.inside: self.text += data

def read(name):
    page = Page(); page.feed(open(os.path.join(folder, name)).read()); return page

good = read('check.dom')
assert good.checked, 'the load handler did not run (page not loaded?)'
w = good.widths
assert w['scroll-width'] <= 1280, f'the page scrolls sideways in a 1280-pixel window ({w["scroll-width"]:.0f} px wide)'
assert w['widest'] <= w['body-right'] + 1, f'a table or image reaches x {w["widest"]:.0f}, past the body ({w["body-right"]:.0f})'
# A step with a path shows its first frame, then its middle and last frames beside it.
path_steps = [i for i, s in enumerate(tour['steps']) if s.get('path')]
assert len(good.images) == len(captions) + 2 * len(path_steps), f'{len(good.images)} images for {len(captions)} steps'
for src, width in good.images:
    assert os.path.exists(os.path.join(folder, src)), f'{src} is not in the folder'
    assert width is not None and int(width) > 0, f'{src} did not load in the browser (naturalWidth {width})'
assert good.captions == captions, f'captions differ from the tour file:\n{good.captions}\n{captions}'
if os.path.exists(os.path.join(folder, 'broken.dom')):
    bad = read('broken.dom')
    assert bad.checked and int(bad.images[0][1]) == 0, 'a missing image was not detected: the check cannot tell'
markdown = open(os.path.join(folder, 'README.md')).read()
for i, caption in enumerate(captions):
    assert f'(step-{i + 1:02d}.png)' in markdown, f'README.md lacks step-{i + 1:02d}.png'
    assert caption in ' '.join(markdown.split()), f'README.md lacks the caption of step {i + 1}'
# The figures: one row per technique of a step, an error for all but the reference, a time.
rows = re.findall(r'<tr><td>(.*?)</td><td>(.*?)</td><td>(.*?)</td>.*?<td>([0-9.]+)</td><td>[0-9.]+</td></tr>',
                  open(os.path.join(folder, 'index.html')).read())
steps_with_compare = sum(1 for s in tour['steps'] if s.get('compare'))
assert len(rows) == len(captions) + steps_with_compare, f'{len(rows)} figure rows'
for name, reference, mae, ms in rows:
    assert reference in ('hard', 'soft'), (name, reference)
    assert 0.0 <= float(mae) <= 1.0 and float(ms) > 0.0, (name, mae, ms)
# Path steps: the strip's frames differ (the path moves the camera), and the page gives the
# temporal error of each; on large-scenes the unsnapped crop under the dolly flickers, snapped not.
page_text = open(os.path.join(folder, 'index.html')).read()
flicker = {}
for i in path_steps:
    from PIL import Image
    first, last = (Image.open(os.path.join(folder, f'step-{i + 1:02d}{suffix}.png')).convert('RGB')
                   for suffix in ('', '-last'))
    diff = sum(abs(a - b) for p, q in zip(first.getdata(), last.getdata()) for a, b in zip(p, q))
    assert diff / (3 * first.width * first.height) > 1.0, f'step {i + 1}: the path did not move the view'
    section = page_text.split(f'<section id="step-{i + 1}">')[1].split('</section>')[0]
    found = re.search(r'temporal error \(flicker\) ([0-9.]+) mean', section)
    assert found, f'step {i + 1}: no temporal error on the page'
    flicker[tour['steps'][i]['title']] = float(found.group(1))
if tour['title'] == 'Large scenes':
    unsnapped = flicker['Shimmer: the crop slides under a sub-texel dolly']
    snapped = flicker['The same dolly with snapping']
    assert unsnapped > 1e-4 and unsnapped > 2 * snapped, f'dolly flicker: unsnapped {unsnapped}, snapped {snapped}'
    print(f'dolly: temporal error unsnapped {unsnapped}, snapped {snapped}')
# Every expectation of the tour file is on the page beside its caption, none of them failed.
expectations = sum(len(v) if isinstance(v, list) else 1 for s in tour['steps'] for v in s.get('expect', {}).values())
assert 'class="failed"' not in page_text, 'an expectation failed on the page'
assert page_text.count('<li class="passed">') == expectations, f'{page_text.count("<li class=")} marks, {expectations} expectations'
print(f'ok: {os.path.basename(folder)}: {expectations} expectations passed; {len(good.images)} images loaded in Chromium, {len(captions)} captions, '
      f'{len(rows)} rows of figures')
PY
done
