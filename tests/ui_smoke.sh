#!/usr/bin/env bash
# Smoke test of the interactive app under Xvfb: it must open its window with the UI, draw the
# frames while switching techniques, save a screenshot that is not blank, and exit with 0.
set -euo pipefail
xvfb_run=$1 shadowlab=$2 screenshot=$3
rm -f "$screenshot"
"$xvfb_run" -a -s "-screen 0 1280x800x24" "$shadowlab" --backend glfw --size 960x600 --smoke-test 300 \
  --screenshot "$screenshot" --quiet
[ -s "$screenshot" ] || { echo "FAIL: no screenshot at $screenshot"; exit 1; }
python3 - "$screenshot" <<'PY'
import struct, sys, zlib
data = open(sys.argv[1], 'rb').read()
assert data[:8] == b'\x89PNG\r\n\x1a\n', 'not a PNG'
width, height = struct.unpack('>II', data[16:24])
assert (width, height) == (960, 600), f'unexpected size {width}x{height}'
# Decode IDAT and count distinct colours: a blank or single-colour window fails.
idat, pos = b'', 8
while pos < len(data):
    length, kind = struct.unpack('>I4s', data[pos:pos + 8])
    if kind == b'IDAT':
        idat += data[pos + 8:pos + 8 + length]
    pos += 12 + length
raw = zlib.decompress(idat)
colours = len(set(raw[i:i + 3] for i in range(1, len(raw), 97)))
assert colours > 20, f'only {colours} colours: blank window?'
print(f'ok: {width}x{height} screenshot with {colours}+ distinct colours')
PY
