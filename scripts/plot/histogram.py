#!/usr/bin/env python3
"""Overlaid histograms of a CSV column, one semi-transparent series per group, on equal bins spanning
all values (the bins vaegail prints as a table beside the figure).

python3 scripts/plot/histogram.py --csv eval/speeds.csv --column value --group-by series --out speeds.png
"""
import numpy as np

import plotlib


def draw(args):
    table = plotlib.read_csv(args.csv)
    values = np.array(plotlib.numbers(table, args.column))
    if args.group_by:
        cells = plotlib.strings(table, args.group_by)
        groups = np.array(cells)
        names = plotlib.group_order(cells)
        series = [(f"{args.group_prefix}{name}", values[groups == name]) for name in names]
    else:
        series = [("", values)]
    lo, hi = values.min(), values.max()
    if lo == hi:  # one value: a bin around it
        half = 0.5 if lo == 0 else abs(lo) * 0.1
        lo, hi = lo - half, hi + half
    edges = np.linspace(lo, hi, args.bins + 1)
    fig, ax = plotlib.figure(args, args.xlabel or args.column, args.ylabel)
    for (name, group), color in zip(series, plotlib.series_colors(len(series))):
        ax.hist(group, bins=edges, color=color, alpha=0.45, label=name or None)
        ax.hist(group, bins=edges, color=color, histtype="step", linewidth=1.2)
    if args.group_by:
        ax.legend()
    plotlib.save(fig, args.out)


if __name__ == "__main__":
    p = plotlib.parser(__doc__.splitlines()[0])
    p.add_argument("--csv", required=True, help="CSV with a header row")
    p.add_argument("--column", required=True, help="numeric column to count")
    p.add_argument("--group-by", default="", help="column whose values split the rows into series")
    p.add_argument("--group-prefix", default="", help="text before each group's name in the legend")
    p.add_argument("--bins", type=int, default=40, help="equal-width bins over the column's range (default 40)")
    p.add_argument("--xlabel", default="", help="x axis label (default: the column's name)")
    p.add_argument("--ylabel", default="count", help="y axis label (default: count)")
    args = p.parse_args()
    if args.bins < 1:
        p.error("--bins must be at least 1")
    plotlib.run(draw, args)
