#!/usr/bin/env python3
"""scripts/bench_tables.py BENCH.jsonl [DOC.md] — the quick bench's tables for docs/bench.md.

Reads the JSON lines `shadowlab bench` printed (rows and claims) and prints two Markdown tables:
the default variant of every technique per scene (plus the variants the claims use), and the
claims with their verdicts. With DOC.md it replaces the text between the markers
<!-- bench-quick:begin --> and <!-- bench-quick:end --> in that file instead, so the numbers in
the docs are the run's, never typed by hand. Usage (the main job writes bench.jsonl):

  build/bin/shadowlab bench --quick --csv bench.csv --out out/bench > bench.jsonl
  python3 scripts/bench_tables.py bench.jsonl docs/bench.md
"""
import json
import sys

CLAIM_VARIANTS = {"compare=nearest", "samples=1", "blur=5", "width-from-light"}


def fmt(v, digits):
    return "-" if v is None else f"{v:.{digits}f}"


def tables(lines):
    rows = [r for r in lines if "technique" in r and "claim" not in r]
    claims = [r for r in lines if "claim" in r]
    out = []
    first = rows[0] if rows else {}
    err = first.get("error", {})
    out.append(
        f"Errors by the {err.get('metric', 'area')} metric of [error.md](error.md) against the "
        "primary truth (`reference.hard pixel=area`; `reference.soft pixel=area` for smoothies), "
        "over the scored pixels (*left out*: the share of pixels not scored); *RMSE point* by the "
        "point metric (`pixel=centre`). Made by: " + first.get("command", "shadowlab bench --quick")
        + (f" at commit {first['commit']}" if "commit" in first else "") + ".")
    out.append("")
    out.append("| scene | technique | variant | frame ms | RMSE | RMSE point | max | >0.5 | band RMSE "
               "| leak | temporal | reference temporal | left out |")
    out.append("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        if r.get("status") != "ok":
            continue
        if r["variant"] != "default" and r["variant"] not in CLAIM_VARIANTS:
            continue
        e = r["error"]
        soft = r.get("reference", "").startswith("reference.soft")
        point = r.get("vs_reference_soft_centre" if soft else "vs_reference_hard_centre", {})
        out.append("| " + " | ".join([
            r["scene"], r["technique"], r["variant"], fmt(r.get("frame_ms"), 1),
            fmt(e["rmse"], 4), fmt(point.get("rmse"), 4), fmt(e["max_abs"], 2),
            fmt(e["share_above_half"], 4), fmt(e["band_rmse"], 3), fmt(e["leak_share"], 4),
            fmt(r.get("temporal_change"), 5), fmt(r.get("reference_temporal_change"), 5),
            fmt(e.get("left_out", {}).get("share"), 3)]) + " |")
    out.append("")
    out.append("| claim | source | scene | setup | measured | verdict |")
    out.append("|---|---|---|---|---|---|")
    for c in claims:
        out.append("| " + " | ".join(c[k].replace("|", "/") for k in
                                       ("statement", "source", "scene", "setup", "measured",
                                        "verdict")) + " |")
    return "\n".join(out) + "\n"


def main():
    if len(sys.argv) not in (2, 3):
        sys.stderr.write(__doc__)
        sys.exit(2)
    with open(sys.argv[1], encoding="utf-8") as f:
        lines = [json.loads(line) for line in f if line.strip()]
    text = tables(lines)
    if len(sys.argv) == 2:
        sys.stdout.write(text)
        return
    begin, end = "<!-- bench-quick:begin -->", "<!-- bench-quick:end -->"
    with open(sys.argv[2], encoding="utf-8") as f:
        doc = f.read()
    if begin not in doc or end not in doc:
        sys.stderr.write(f"{sys.argv[2]}: no {begin} ... {end} markers\n")
        sys.exit(2)
    head, rest = doc.split(begin, 1)
    _, tail = rest.split(end, 1)
    with open(sys.argv[2], "w", encoding="utf-8") as f:
        f.write(head + begin + "\n" + text + end + tail)


if __name__ == "__main__":
    main()
