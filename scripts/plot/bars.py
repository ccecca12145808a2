#!/usr/bin/env python3
"""Grouped bars: one group per category along x, one bar per series in each, a value on each bar:
the humanoid's falls per controller, VAE policy beside the fine-tuned one (the paper's Figure 5,
right; `vaegail eval humanoid`).

The CSV holds one row per bar: group (x tick; groups in order of first appearance), series
(legend text; series in order of first appearance), value (bar height). A group without a row
for some series has no bar there.

python3 scripts/plot/bars.py --csv eval/falls.csv --ylabel "falls (%)" --out falls.png
"""
import plotlib


def draw(args):
    table = plotlib.read_csv(args.csv)
    group, series = plotlib.strings(table, "group"), plotlib.strings(table, "series")
    value = plotlib.numbers(table, "value")
    groups = list(dict.fromkeys(group))
    names = list(dict.fromkeys(series))
    width = 0.8 / len(names)
    fig, ax = plotlib.figure(args, args.xlabel, args.ylabel)
    for k, (name, color) in enumerate(zip(names, plotlib.series_colors(len(names)))):
        xs, heights = [], []
        for g, s, v in zip(group, series, value):
            if s == name:
                xs.append(groups.index(g) - 0.4 + width * (k + 0.5))
                heights.append(v)
        bars = ax.bar(xs, heights, width=width, color=color, label=name)
        ax.bar_label(bars, fmt=args.value_format, fontsize=8)
    ax.set_xticks(range(len(groups)), groups, rotation=30 if len(groups) > 4 else 0, ha="right" if len(groups) > 4 else "center")
    ax.grid(False, axis="x")
    ax.margins(y=0.15)  # room above the tallest bar for its number and the legend
    ax.legend()
    plotlib.save(fig, args.out)


if __name__ == "__main__":
    p = plotlib.parser(__doc__.splitlines()[0])
    p.add_argument("--csv", required=True, help="CSV with columns group, series, value")
    p.add_argument("--xlabel", default="", help="x axis label (default: none)")
    p.add_argument("--ylabel", default="value", help="y axis label (default: value)")
    p.add_argument("--value-format", default="%.0f", help="printf format of the number on each bar (default %%.0f)")
    plotlib.run(draw, p.parse_args())
