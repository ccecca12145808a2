#!/usr/bin/env python3
"""2-D paths in equal units on both axes, a dot at each start and a square at each end: the arm's
end-effector paths seen from above, demonstrations solid and imitations dashed (the paper's
Figures 2 and 3).

The CSV holds one row per point: path (which polyline), group (paths of a group share a colour),
label (legend text; empty: none), style (solid or dashed), x, y.

python3 scripts/plot/paths.py --csv eval/reach_paths.csv --out reach_paths.png
"""
import plotlib


def draw(args):
    table = plotlib.read_csv(args.csv)
    path, group = plotlib.strings(table, "path"), plotlib.strings(table, "group")
    label, style = plotlib.strings(table, "label"), plotlib.strings(table, "style")
    x, y = plotlib.numbers(table, "x"), plotlib.numbers(table, "y")
    paths = {}  # path id -> row indices, in order of first appearance
    for i, p in enumerate(path):
        paths.setdefault(p, []).append(i)
    if args.colormap == "viridis":  # groups are numbers in [0, 1]
        color_of = {g: plotlib.plt.get_cmap("viridis")(float(g)) for g in set(group)}
    else:
        names = plotlib.group_order(group)
        color_of = dict(zip(names, plotlib.series_colors(len(names))))
    fig, ax = plotlib.figure(args, args.xlabel, args.ylabel)
    for rows in paths.values():
        first = rows[0]
        if style[first] not in ("solid", "dashed"):
            raise plotlib.FigureError(f"{args.csv}: line {first + 2}: style must be solid or dashed, not '{style[first]}'")
        px, py = [x[i] for i in rows], [y[i] for i in rows]
        color = color_of[group[first]]
        ax.plot(px, py, color=color, linestyle="--" if style[first] == "dashed" else "-", linewidth=1.3,
                label=label[first] or None)
        ax.plot(px[0], py[0], "o", color=color, markersize=4)
        ax.plot(px[-1], py[-1], "s", color=color, markersize=5)
    ax.set_aspect("equal", adjustable="datalim")
    if any(label):
        ax.legend()
    plotlib.save(fig, args.out)


if __name__ == "__main__":
    p = plotlib.parser(__doc__.splitlines()[0])
    p.add_argument("--csv", required=True, help="CSV with columns path, group, label, style, x, y")
    p.add_argument("--colormap", choices=["tab10", "viridis"], default="tab10",
                   help="tab10: a colour per group; viridis: groups are numbers in [0, 1] (default tab10)")
    p.add_argument("--xlabel", default="x", help="x axis label")
    p.add_argument("--ylabel", default="y", help="y axis label")
    plotlib.run(draw, p.parse_args())
