#!/usr/bin/env python3
"""Error against frame time from a sweep, one PNG per view (docs/python.md "Examples").

    PYTHONPATH=build/python /usr/bin/python3 examples/sweep_plot.py [--spec SPEC.json] [--out DIR]

Without --spec: four GLSL techniques on fence at 256x192 over three shadow-map sides. Each
point is a row: its frame time (median of the timed frames) and its RMSE against the row's
primary reference (reference.hard pixel=area, or reference.soft for smoothies), log axes, one
series per technique with each point's variant, the view's Pareto front as a line. The PNGs carry the spec and the commit.
"""

import argparse
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402

import shadowlab  # noqa: E402

DEFAULT_SPEC = {"techniques": ["modern.hw", "modern.pcf", "modern.gems16", "modern.vsm"],
                "scenes": ["fence"], "sizes": ["256x192"], "shadow_maps": [256, 512, 1024]}


def primary_rmse(rows):
    """Each row's RMSE against its primary reference (the bench's "reference" column)."""
    soft = rows["reference"].str.startswith("reference.soft")
    return rows["soft_rmse"].where(soft, rows["hard_rmse"])


def plot_view(rows, title, path, provenance):
    fig, ax = plt.subplots(figsize=(8, 5), dpi=100)
    for technique, group in rows.groupby("technique", sort=False):
        ax.plot(group["frame_ms"], primary_rmse(group), "o", label=technique)
        for x, y, variant in zip(group["frame_ms"], primary_rmse(group), group["variant"]):
            ax.annotate(variant, (x, y), textcoords="offset points", xytext=(4, 4), fontsize=7)
    front = rows[rows["pareto_rank"] == 1].sort_values("frame_ms")
    ax.plot(front["frame_ms"], primary_rmse(front), "-", color="grey", lw=1,
            label="Pareto front", zorder=0)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("frame time, ms (median of the timed frames)")
    ax.set_ylabel(f"RMSE against {rows['reference'].iloc[0]}")
    ax.set_title(title)
    ax.legend(fontsize="small")
    fig.tight_layout()
    fig.savefig(path, metadata=provenance)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--spec", help="a sweep spec as a JSON file [four techniques on fence]")
    parser.add_argument("--out", default="out/sweep-plot", help="output folder [out/sweep-plot]")
    args = parser.parse_args()
    spec = DEFAULT_SPEC
    if args.spec:
        with open(args.spec, encoding="utf-8") as f:
            spec = json.load(f)
    try:
        rows = shadowlab.sweep(spec)
    except ValueError as e:  # the spec: one line, exit 2 as the CLI's bad input
        print(f"sweep_plot: {e}", file=sys.stderr)
        return 2
    os.makedirs(args.out, exist_ok=True)
    rows = rows[(rows["status"] == "ok") & ~rows["technique"].str.startswith("reference.")]
    provenance = {"Software": f"shadowlab {shadowlab.commit()} (examples/sweep_plot.py)",
                  "shadowlab:command": " ".join([sys.executable, *sys.argv]),
                  "shadowlab:parameters": json.dumps(spec)}
    rows.to_csv(os.path.join(args.out, "sweep.csv"), index=False)
    for (scene, width, height, orbit), view in rows.groupby(
            ["scene", "width", "height", "orbit"], sort=False):
        name = f"{scene}-{width}x{height}" + (f"-orbit{orbit.replace(',', '_')}" if orbit else "")
        path = os.path.join(args.out, f"sweep-{name}.png")
        plot_view(view, f"{scene}, {width}x{height}" + (f", orbit {orbit}" if orbit else ""),
                  path, provenance)
        print(f"sweep_plot: wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
