#!/usr/bin/env python3
"""Time series in small multiples, one panel per group, one line per series, an x-range shaded in
every panel: the walker's forward speed through a transition between behaviours, the blend
window shaded (`vaegail eval transitions`).

The CSV holds one row per point: panel (panel title; panels in order of first appearance),
series (legend text; a series keeps its colour across panels), style (solid or dashed), x, y.

python3 scripts/plot/timeseries.py --csv transitions/speed_over_time.csv --shade 5,5.5 --smooth 40 --out speed.png
"""
import math

import plotlib


def running_mean(values, window):
    """The mean of the last `window` values at each point (fewer at the start)."""
    out, total = [], 0.0
    for i, v in enumerate(values):
        total += v
        if i >= window:
            total -= values[i - window]
        out.append(total / min(i + 1, window))
    return out


def draw(args):
    table = plotlib.read_csv(args.csv)
    panel, series = plotlib.strings(table, "panel"), plotlib.strings(table, "series")
    style = plotlib.strings(table, "style")
    x, y = plotlib.numbers(table, "x"), plotlib.numbers(table, "y")
    panels = list(dict.fromkeys(panel))
    names = list(dict.fromkeys(series))
    color_of = dict(zip(names, plotlib.series_colors(len(names))))
    shade = None
    if args.shade:
        try:
            shade = [float(v) for v in args.shade.split(",")]
        except ValueError:
            shade = []
        if len(shade) != 2:
            raise plotlib.FigureError(f"--shade: two numbers FROM,TO expected, not '{args.shade}'")
    if args.smooth < 1:
        raise plotlib.FigureError(f"--smooth: at least 1 point, not {args.smooth}")

    columns = min(args.columns, len(panels))
    rows = math.ceil(len(panels) / columns)
    dpi = 100
    fig, axes = plotlib.plt.subplots(rows, columns, figsize=(args.width / dpi, args.height / dpi), dpi=dpi,
                                     layout="constrained", squeeze=False, sharex=True, sharey=True)
    fig.suptitle(args.title)
    for k, ax in enumerate(axes.flat):
        if k >= len(panels):
            ax.axis("off")
            continue
        ax.set_title(panels[k], fontsize="small")
        ax.grid(True, color="0.9")
        ax.set_axisbelow(True)
        if shade:
            ax.axvspan(shade[0], shade[1], color="0.85")
        for name in names:
            points = [i for i in range(len(x)) if panel[i] == panels[k] and series[i] == name]
            if not points:
                continue
            if style[points[0]] not in ("solid", "dashed"):
                raise plotlib.FigureError(
                    f"{args.csv}: line {points[0] + 2}: style must be solid or dashed, not '{style[points[0]]}'")
            ax.plot([x[i] for i in points], running_mean([y[i] for i in points], args.smooth), color=color_of[name],
                    linestyle="--" if style[points[0]] == "dashed" else "-", linewidth=1.2,
                    label=name if k == 0 else None)
        if k % columns == 0:
            ax.set_ylabel(args.ylabel)
        if k >= len(panels) - columns:
            ax.set_xlabel(args.xlabel)
    axes.flat[0].legend(fontsize="x-small")
    plotlib.save(fig, args.out)


if __name__ == "__main__":
    p = plotlib.parser(__doc__.splitlines()[0])
    p.add_argument("--csv", required=True, help="CSV with columns panel, series, style, x, y")
    p.add_argument("--shade", default="", help="FROM,TO: the x-range to shade in every panel")
    p.add_argument("--smooth", type=int, default=1, help="running mean over this many points (default 1: none)")
    p.add_argument("--columns", type=int, default=2, help="panels per row (default 2)")
    p.add_argument("--xlabel", default="x", help="x axis label")
    p.add_argument("--ylabel", default="y", help="y axis label")
    plotlib.run(draw, p.parse_args())
