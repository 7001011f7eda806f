#!/usr/bin/env bash
# `eval --json` reports every accuracy column a one-row `bench --accuracy` of the same frame
# reports, with the same values (issue 32: one function, bench/accuracy_columns.h, fills both).
# Two frames: translucent-shadows over layered-quads (the translucent receivers' columns and the
# technique's own model, `_own_`), and pcss on contact against a soft reference (the penumbra,
# the reference's floor, the texel footprint). Every accuracy key of the bench row must be in
# eval's "bench_columns" and the other way round, each value equal.
set -euo pipefail
shadowlab=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"

compare() {   # NAME SCENE TECHNIQUE REFERENCE-ARGS...
  name=$1 scene=$2 technique=$3
  shift 3
  "$shadowlab" eval --backend osmesa --scene "$scene" -t "$technique" --size 160x90 --frames 3 "$@" --json \
    >"$name-eval.json" 2>"$name-eval.log" || { cat "$name-eval.log"; echo "FAIL: eval $name"; exit 1; }
  "$shadowlab" bench --backend osmesa --scenes "$scene" --techniques "$technique" --size 160x90 --frames 3 --warmup 1 \
    --accuracy --contact-band "$@" --out "$name-bench.json" >"$name-bench.log" 2>&1 || { cat "$name-bench.log"; echo "FAIL: bench $name"; exit 1; }
  python3 - "$name" "$name-eval.json" "$name-bench.json" <<'PY'
import json, re, sys
name, eval_file, bench_file = sys.argv[1:]
evaluation = json.load(open(eval_file))
rows = json.load(open(bench_file))
rows = rows if isinstance(rows, list) else [rows]
assert len(rows) == 1, f'{name}: {len(rows)} bench rows, expected 1'
row = rows[0]
accuracy = re.compile(r'^(hard_|soft_|footprint_)|^(projection_ratio_median|shadow_maps|technique_penumbra_fraction|translucency_model)$')
bench = {k: v for k, v in row.items() if accuracy.match(k)}
columns = evaluation.get('bench_columns')
assert isinstance(columns, dict), f'{name}: eval --json has no bench_columns'
columns = {k: v for k, v in columns.items() if not k.startswith('seconds_')}   # wall times differ run to run
missing = sorted(set(bench) - set(columns))
extra = sorted(set(columns) - set(bench))
assert not missing, f'{name}: bench reports {missing}, eval --json does not'
assert not extra, f'{name}: eval --json reports {extra}, the bench row does not'
for key, value in bench.items():
    other = columns[key]
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        assert abs(value - other) <= 1e-9 * max(1.0, abs(value)), f'{name}: {key}: bench {value}, eval {other}'
    else:
        assert value == other, f'{name}: {key}: bench {value!r}, eval {other!r}'
# eval's own detail agrees with its columns (the same evaluation).
assert abs(evaluation['accuracy']['hard']['mae'] - columns['hard_mae']) <= 1e-12
print(f'ok: {name}: {len(bench)} accuracy columns, the same keys and values in bench and eval --json')
PY
}

compare translucent layered-quads translucent-shadows --reference both --samples 16
python3 - translucent-eval.json <<'PY'
import json, sys
columns = json.load(open(sys.argv[1]))['bench_columns']
for key in ('hard_translucent_mae', 'hard_own_translucent_mae', 'soft_translucent_pixels', 'hard_own_mae'):
    assert key in columns, f'the translucent frame lacks {key}: the receivers were not measured'
assert columns['hard_translucent_layers'] == 2, columns['hard_translucent_layers']
PY
compare soft contact pcss --reference both --samples 64
python3 - soft-eval.json <<'PY'
import json, sys
columns = json.load(open(sys.argv[1]))['bench_columns']
assert columns['soft_reference_rays'] == 64 and columns['soft_reference_floor'] > 0, columns
assert columns['shadow_maps'] >= 1 and columns['footprint_median'] > 0, columns
PY
echo "ok: eval --json and bench --accuracy agree"
