#!/usr/bin/env bash
# The report page (issue 14): on a tiny sweep, README.md says how many images it wrote and that
# many are in images/; every technique's image has its error heatmap beside it in one table row
# with a caption (MAE, false-shadow and false-light rates), the reference has none; every column
# of the results table is defined; the parameters column lists only what the sweep changes
# (resolution), not every parameter; false-shadow and false-light columns sit beside the MAEs.
set -euo pipefail
shadowlab=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
unset DISPLAY WAYLAND_DISPLAY
spec=$(cd "$(dirname "$0")" && pwd)/report_quick.json
"$shadowlab" report --backend osmesa --spec "$spec" --out "$tmp/out" --quiet >"$tmp/report.log"
/usr/bin/python3 - "$tmp/out" "$tmp/report.log" <<'PY'
import os, re, sys
out, log = sys.argv[1], open(sys.argv[2]).read()
page = open(os.path.join(out, 'README.md')).read()
files = sorted(os.listdir(os.path.join(out, 'images')))
said = int(re.search(r'(\d+) images in images/', page).group(1))
assert said == len(files), f'the page says {said} images, images/ holds {len(files)}'
assert f'{len(files)} images' in log, f'the summary line does not say {len(files)} images: {log}'
linked = re.findall(r'\]\(images/([^)]+)\)', page)
assert sorted(linked) == files, f'linked images differ from the files written: {set(linked) ^ set(files)}'
rows = [l for l in page.splitlines() if l.startswith('| **')]
assert rows, 'no image rows'
for row in rows:
    images = re.findall(r'\(images/([^)]+)\)', row)
    name = re.search(r'\(`([^`]+)`\)', row).group(1)
    if name == 'reference':
        assert images == ['cube-reference.png'], row
        continue
    assert images == [f'cube-{name}.png', f'cube-{name}-error.png'], f'image and heatmap not side by side: {row}'
    assert re.search(r'MAE [0-9.]+, false shadow [0-9.]+%, false light [0-9.]+%', row), f'no caption figures: {row}'
header = next(l for l in page.splitlines() if l.startswith('| scene | technique'))
columns = [c.strip() for c in header.strip('|').split('|')]
for column in columns:
    assert f'**{column}**' in page, f'column "{column}" is not defined'
for wanted in ('false shadow hard', 'false light hard', 'false shadow soft', 'false light soft'):
    assert wanted in columns, f'no column {wanted}'
table = [l for l in page.splitlines() if l.startswith('| cube | ')]
assert len(table) == 4, table
for line in table:
    cells = [c.strip() for c in line.strip('|').split('|')]
    assert re.fullmatch(r'resolution=(512|1024)', cells[2]), f'parameters should list only the swept one: {cells[2]}'
    assert cells[9].endswith('%') and cells[10].endswith('%'), line
print(f'ok: {len(files)} images said and written, {len(rows)} image rows with heatmaps, {len(columns)} columns defined')
PY
