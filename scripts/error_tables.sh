#!/usr/bin/env bash
# scripts/error_tables.sh [DOC.md] — the measured tables of docs/error.md, from `shadowlab
# compare` runs (nothing typed by hand): the exact shadow volumes under the point metric on
# every closed-caster scene, and volumes against a 512² shadow map (bilinear 2x2 compare and
# nearest) under the area metric at three window sizes. Prints Markdown; with DOC.md, replaces
# the text between <!-- error-axis:begin --> and <!-- error-axis:end --> there.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=build/bin/shadowlab
[[ -x $bin ]] || { echo "error_tables.sh: build first (scripts/build.sh shadowlab)" >&2; exit 2; }
out=$(mktemp)
trap 'rm -f "$out" "$out.md"' EXIT
commit=$("$bin" compare --scene analytic --size 16x16 --a modern.volumes --b reference.hard |
         python3 -c 'import json,sys; print(json.load(sys.stdin)["commit"])')

# Point metric: modern.volumes against reference.hard (pixel centres), 400x300.
for scene in analytic brabec fence trees dueling ball bleeding boxes bunny contact cubes cylinder \
    fill-bound squares dragon teapot; do
  "$bin" compare --scene "$scene" --size 400x300 --a modern.volumes --b reference.hard \
    2>/dev/null | sed "s/^/point $scene /" >> "$out" || echo "point $scene {}" >> "$out"
done
# Area metric: volumes and modern.hw (512²) against reference.hard pixel=area.
for size in 256x192 400x300 800x600; do
  for scene in brabec fence; do
    for t in "modern.volumes" "modern.hw" "modern.hw --a-param compare=nearest"; do
      "$bin" compare --scene "$scene" --size "$size" --a $t --b reference.hard \
        --b-param pixel=area | sed "s/^/area $scene /" >> "$out"
    done
  done
done

python3 - "$out" "$commit" > "$out.md" <<'PY'
import json, sys
path, commit = sys.argv[1], sys.argv[2]
point, area = [], []
for line in open(path):
    kind, scene, rest = line.split(" ", 2)
    d = json.loads(rest)
    if not d:
        continue
    (point if kind == "point" else area).append((scene, d))
print(f"Made by `scripts/error_tables.sh` at commit {commit} (`shadowlab compare`, 2 cores).")
print()
print("**Point metric, modern.volumes against reference.hard, 400x300** (scored pixels that "
      "differ; all pixels beside it, terminators included):")
print()
print("| scene | scored pixels | differ | share | RMSE | left out | faces away | all pixels differ |")
print("|---|---|---|---|---|---|---|---|")
for scene, d in point:
    lo = d["left_out"]
    print(f"| {scene} | {d['scored_pixels']} | {d['mismatching']} | "
          f"{100 * d['mismatching'] / max(1, d['scored_pixels']):.3f}% | {d['rmse']:.4f} | "
          f"{100 * lo['share']:.1f}% | {lo['faces_away']} | {d['all_pixels']['mismatching']} |")
print()
print("**Area metric (antialiasing), RMSE against reference.hard pixel=area**, 512² map for "
      "modern.hw (default: bilinear 2x2 depth compare; nearest: one comparison):")
print()
print("| size | scene | modern.volumes | modern.hw | modern.hw compare=nearest |")
print("|---|---|---|---|---|")
rows = {}
for scene, d in area:
    t = d["a"] + (" nearest" if d.get("a_params", {}).get("compare") == "nearest" else "")
    rows.setdefault((d["size"], scene), {})[t] = d["rmse"]
for (size, scene), r in rows.items():
    print(f"| {size} | {scene} | {r.get('modern.volumes', float('nan')):.4f} | "
          f"{r.get('modern.hw', float('nan')):.4f} | {r.get('modern.hw nearest', float('nan')):.4f} |")
PY

if [[ $# -eq 0 ]]; then cat "$out.md"; exit 0; fi
python3 - "$1" "$out.md" <<'PY'
import sys
doc, table = sys.argv[1], open(sys.argv[2]).read()
begin, end = "<!-- error-axis:begin -->", "<!-- error-axis:end -->"
text = open(doc).read()
if begin not in text or end not in text:
    sys.exit(f"{doc}: no {begin} ... {end} markers")
head, rest = text.split(begin, 1)
_, tail = rest.split(end, 1)
open(doc, "w").write(head + begin + "\n" + table + end + tail)
PY
