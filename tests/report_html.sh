#!/usr/bin/env bash
# The report's index.html (issue 32), checked in a real browser: the report is run on the tests'
# quick spec (report_quick.json) on OSMesa, then the page is opened in headless Chromium from a
# copy of the whole out folder moved elsewhere (its images are relative links: the folder is the
# unit). As tour_html.sh does, a copy of the page with a small load handler added (index.html has
# no script) records each image's naturalWidth, and --dump-dom prints the DOM after it. Checked:
# the page loads; it fetches nothing from a network; every image loads (naturalWidth > 0), every
# chart and every file in images/ is on it; the results table has one row per row of results.json,
# in order, with its scene, technique and frame ms; the machine table has the GPU and the commit.
# A copy with one image pointing at a missing file must fail the image check, so the check can tell.
#   report_html.sh SHADOWLAB CHROMIUM
set -euo pipefail
shadowlab=$1
chromium=$2
spec=$(cd "$(dirname "$0")" && pwd)/report_quick.json
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
unset DISPLAY WAYLAND_DISPLAY
cd "$tmp"

# dump PAGE OUT: the DOM of PAGE after its load event, from a fresh profile, nothing fetched.
dump() {
  rm -rf "$tmp/profile"
  timeout 120 "$chromium" --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
    --disable-background-networking --disable-component-update --disable-sync --user-data-dir="$tmp/profile" \
    --virtual-time-budget=10000 --dump-dom "file://$1" >"$2" 2>"$tmp/chromium.log" ||
    { cat "$tmp/chromium.log"; echo "FAIL: chromium failed on $1"; exit 1; }
}

"$shadowlab" report --backend osmesa --spec "$spec" --out "$tmp/out" --quiet >"$tmp/report.log"
grep -q "README.md and index.html" "$tmp/report.log" || { cat "$tmp/report.log"; echo "FAIL: no index.html said"; exit 1; }
mv "$tmp/out" "$tmp/moved"
page="$tmp/moved/index.html"
! grep -qi "<script" "$page" || { echo "FAIL: $page has a script"; exit 1; }
! grep -Eqi '(src|href)="(https?:)?//|url\(' "$page" || { echo "FAIL: $page refers to something outside the folder"; exit 1; }
sed 's#</body>#<script>window.addEventListener("load", () => { for (const i of document.images) i.dataset.naturalWidth = i.naturalWidth; document.body.dataset.checked = "yes"; });</script></body>#' \
  "$page" >"$tmp/moved/check.html"
first=$(grep -o 'src="images/[^"]*"' "$page" | head -1)
sed "0,/$(printf '%s' "$first" | sed 's#/#\\/#g')/s//src=\"images\/missing.png\"/" "$tmp/moved/check.html" >"$tmp/moved/broken.html"
dump "$tmp/moved/check.html" "$tmp/check.dom"
dump "$tmp/moved/broken.html" "$tmp/broken.dom"

/usr/bin/python3 - "$tmp/moved" "$tmp/check.dom" "$tmp/broken.dom" <<'PY'
import html.parser, json, os, sys
folder, good_dom, bad_dom = sys.argv[1:4]

class Page(html.parser.HTMLParser):
    def __init__(self):
        super().__init__()
        self.images, self.rows, self.machine, self.checked = [], [], {}, False
        self.cell = None
        self.in_machine = False
    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == 'img': self.images.append((a.get('src'), a.get('data-natural-width')))
        if tag == 'body': self.checked = a.get('data-checked') == 'yes'
        if tag == 'table' and a.get('id') == 'machine': self.in_machine = True
        if tag == 'tr' and (a.get('class') == 'result' or self.in_machine): self.row = []; self.keep = True
        if tag in ('td', 'th') and getattr(self, 'keep', False): self.cell = ''
    def handle_endtag(self, tag):
        if tag in ('td', 'th') and self.cell is not None: self.row.append(' '.join(self.cell.split())); self.cell = None
        if tag == 'tr' and getattr(self, 'keep', False):
            self.keep = False
            if self.in_machine: self.machine[self.row[0]] = self.row[1]
            else: self.rows.append(self.row)
        if tag == 'table': self.in_machine = False
    def handle_data(self, data):
        if self.cell is not None: self.cell += data

def read(path):
    page = Page(); page.feed(open(path).read()); return page

good = read(good_dom)
assert good.checked, 'the load handler did not run (page not loaded?)'
charts = sorted(f for f in os.listdir(os.path.join(folder, 'charts')) if f.endswith('.png'))
images = sorted(os.listdir(os.path.join(folder, 'images')))
assert charts, 'no charts were drawn'
sources = [src for src, _ in good.images]
assert sorted(sources) == sorted(['charts/' + c for c in charts] + ['images/' + i for i in images]), \
    f'images on the page differ from the files: {set(sources) ^ set(["charts/" + c for c in charts] + ["images/" + i for i in images])}'
for src, width in good.images:
    assert width is not None and int(width) > 0, f'{src} did not load in the browser (naturalWidth {width})'
rows = json.load(open(os.path.join(folder, 'results.json')))
assert len(good.rows) == len(rows) > 0, f'{len(good.rows)} table rows for {len(rows)} measured rows'
for cells, row in zip(good.rows, rows):
    assert cells[0] == row['scene'] and cells[1] == row['technique'], (cells, row['scene'], row['technique'])
    assert cells[4] == f"{row['frame_ms']:.3f}", (cells[4], row['frame_ms'])
    assert cells[-1] == f"{row['depth_prepass_mode']}: {'on' if row['depth_prepass'] else 'off'}", cells[-1]
combinations = {(c[0], c[1], c[2], c[3]) for c in good.rows}
assert len(combinations) == len(rows), f'rows not told apart: {sorted(combinations)}'
assert good.machine.get('GPU') == rows[0]['gpu'], good.machine
assert good.machine.get('commit') == rows[0]['commit'], good.machine
bad = read(bad_dom)
assert bad.checked and int(bad.images[len(charts)][1]) == 0 and bad.images[len(charts)][0] == 'images/missing.png', \
    'a missing image was not detected: the check cannot tell'
print(f'ok: index.html loaded in Chromium from a moved folder: {len(good.images)} images ({len(charts)} charts), '
      f'{len(good.rows)} table rows for {len(rows)} measured rows, machine {good.machine.get("GPU")} at {good.machine.get("commit")}')
PY
