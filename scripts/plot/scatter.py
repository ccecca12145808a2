#!/usr/bin/env python3
"""Scatter of two CSV columns, each point coloured by a third through viridis, with a colour bar:
the t-SNE map of VAE embeddings coloured by average speed (the paper's Figure 4, left).

python3 scripts/plot/scatter.py --csv tsne.csv --x tsne_x --y tsne_y --color achieved_speed --out tsne.png
"""
import plotlib


def draw(args):
    table = plotlib.read_csv(args.csv)
    x, y = plotlib.numbers(table, args.x), plotlib.numbers(table, args.y)
    value = plotlib.numbers(table, args.color)
    fig, ax = plotlib.figure(args, args.xlabel or args.x, args.ylabel or args.y)
    points = ax.scatter(x, y, c=value, cmap="viridis", s=14, linewidths=0)
    fig.colorbar(points, ax=ax, label=args.color)
    plotlib.save(fig, args.out)


if __name__ == "__main__":
    p = plotlib.parser(__doc__.splitlines()[0])
    p.add_argument("--csv", required=True, help="CSV with a header row (e.g. vaegail plot tsne --coords-out)")
    p.add_argument("--x", default="tsne_x", help="column on the x axis (default tsne_x)")
    p.add_argument("--y", default="tsne_y", help="column on the y axis (default tsne_y)")
    p.add_argument("--color", default="achieved_speed", help="numeric column that colours the points")
    p.add_argument("--xlabel", default="", help="x axis label (default: the column's name)")
    p.add_argument("--ylabel", default="", help="y axis label (default: the column's name)")
    plotlib.run(draw, p.parse_args())
