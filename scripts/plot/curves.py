#!/usr/bin/env python3
"""Line chart of CSV columns against one column, e.g. training curves from a run's metrics.csv.

python3 scripts/plot/curves.py --csv RUN/metrics.csv --x epoch --y train_loss,val_loss --log-y --out loss.png
"""
import plotlib


def draw(args):
    table = plotlib.read_csv(args.csv)
    columns = [c for c in args.y.split(",") if c]
    if not columns:
        raise plotlib.FigureError("--y: name at least one column")
    x = plotlib.numbers(table, args.x)
    ylabel = ", ".join(columns) + (" (log scale)" if args.log_y else "")
    fig, ax = plotlib.figure(args, args.x, ylabel)
    if not args.title:
        ax.set_title(args.csv)
    for column, color in zip(columns, plotlib.series_colors(len(columns))):
        y = plotlib.numbers(table, column)
        if args.log_y and min(y) <= 0:
            raise plotlib.FigureError(f"{args.csv}: {column} has values <= 0, which a log scale cannot show")
        ax.plot(x, y, color=color, label=column, marker="." if len(x) <= 50 else None)
    if args.log_y:
        ax.set_yscale("log")
    ax.legend()
    plotlib.save(fig, args.out)


if __name__ == "__main__":
    p = plotlib.parser(__doc__.splitlines()[0])
    p.add_argument("--csv", required=True, help="CSV with a header row (e.g. run/metrics.csv)")
    p.add_argument("--x", default="epoch", help="column on the x axis (default epoch)")
    p.add_argument("--y", required=True, help="comma-separated columns to draw")
    p.add_argument("--log-y", action="store_true", help="logarithmic y axis (values must be positive)")
    plotlib.run(draw, p.parse_args())
