#!/usr/bin/env bash
# Bad input gets a clear message naming the file or value and exit code 2; the app never crashes.
set -uo pipefail
shadowlab=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0

expect() {   # expect CODE PATTERN -- ARGS...
    local code=$1 pattern=$2
    shift 3
    local output
    output=$("$shadowlab" "$@" 2>&1)
    local actual=$?
    if [ "$actual" != "$code" ] || ! grep -q -- "$pattern" <<<"$output"; then
        echo "FAIL: shadowlab $* -> exit $actual (want $code), output:"
        echo "$output" | sed 's/^/    /'
        failures=$((failures + 1))
    else
        echo "ok: shadowlab $* -> $code, '$pattern'"
    fi
}

echo '{"name": "broken", "objects": [' > "$tmp/broken.json"
echo '{"objects": [{"shape": "cone"}]}' > "$tmp/cone.json"
expect 2 "broken.json" -- render --backend osmesa --scene "$tmp/broken.json" --out "$tmp/a.png"
expect 2 "cone" -- render --backend osmesa --scene "$tmp/cone.json" --out "$tmp/a.png"
expect 2 "no-such-scene" -- render --backend osmesa --scene no-such-scene --out "$tmp/a.png"
expect 2 "out of range" -- render --backend osmesa -t shadowmap --set resolution=10 --out "$tmp/a.png"
expect 2 "has no parameter 'kernel'" -- render --backend osmesa -t shadowmap --set kernel=3 --out "$tmp/a.png"
expect 2 "no such technique" -- render --backend osmesa -t nonexistent --out "$tmp/a.png"
expect 2 "expected glfw, egl or osmesa" -- render --backend vulkan --out "$tmp/a.png"
expect 2 "WIDTHxHEIGHT" -- render --backend osmesa --size 12by3 --out "$tmp/a.png"
expect 2 "no debug image 'nope'" -- render --backend osmesa -t shadowmap --view nope --out "$tmp/a.png"
expect 0 "wrote" -- render --backend osmesa -t shadowmap --view "shadow map" --size 64x48 --out "$tmp/map.png"
[ -s "$tmp/map.png" ] || { echo "FAIL: no PNG written"; failures=$((failures + 1)); }
expect 0 '"id": "shadowmap"' -- list --json

[ $failures = 0 ] || { echo "$failures failure(s)"; exit 1; }
echo "all CLI error checks passed"
