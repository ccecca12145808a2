"""What every figure script shares: the common options, CSV columns by name, one-line errors and
a figure file that appears whole or not at all.

The scripts under scripts/plot/ draw the CSV files vaegail writes; `vaegail plot ...`, `vaegail eval ...`
and `vaegail data info --histogram` run them (the binary carries a copy of each), and each also runs on
its own: python3 scripts/plot/curves.py --help.
"""
import argparse
import csv
import math
import os
import sys

try:
    import matplotlib

    matplotlib.use("Agg")  # files only: no display needed
    import matplotlib.pyplot as plt
except ImportError:
    sys.exit(f"{os.path.basename(sys.argv[0])}: error: needs matplotlib (apt-get install python3-matplotlib)")


class FigureError(Exception):
    """Bad input for a figure; reported as one line."""


def parser(description):
    """An argument parser with the options every figure has."""
    p = argparse.ArgumentParser(description=description)
    p.add_argument("--out", required=True, help="figure to write; the extension picks the format (.png, .svg, .pdf)")
    p.add_argument("--title", default="", help="figure title")
    p.add_argument("--width", type=int, default=960, help="width in pixels (default 960)")
    p.add_argument("--height", type=int, default=640, help="height in pixels (default 640)")
    return p


def read_csv(path):
    """The file's columns by name, as lists of strings; rows in file order."""
    try:
        with open(path, newline="") as f:
            rows = [row for row in csv.reader(f) if row]
    except OSError as e:
        raise FigureError(f"{path}: {e.strerror}")
    if not rows:
        raise FigureError(f"{path}: no header row")
    header, body = rows[0], rows[1:]
    for line, row in enumerate(body, start=2):
        if len(row) != len(header):
            raise FigureError(f"{path}: line {line}: {len(row)} cells, the header has {len(header)}")
    return {"path": path, "columns": {name: [row[i] for row in body] for i, name in enumerate(header)}}


def strings(table, column):
    columns = table["columns"]
    if column not in columns:
        raise FigureError(f"{table['path']}: no column '{column}' (columns: {', '.join(columns)})")
    return columns[column]


def numbers(table, column):
    """A column as finite floats; the error names the file, line and column."""
    values = []
    for line, cell in enumerate(strings(table, column), start=2):
        try:
            value = float(cell)
        except ValueError:
            value = math.nan
        if not math.isfinite(value):
            raise FigureError(f"{table['path']}: line {line}: {column} is not a finite number ('{cell}')")
        values.append(value)
    if not values:
        raise FigureError(f"{table['path']}: no rows to plot")
    return values


def group_order(cells):
    """The distinct values of a group column: sorted as numbers when every one is a number (target
    speeds), else in order of first appearance (the order vaegail wrote its series in)."""
    names = list(dict.fromkeys(cells))

    def number(name):
        try:
            return float(name)
        except ValueError:
            return None

    if all(number(n) is not None for n in names):
        return sorted(names, key=number)
    return names


def series_colors(n):
    """matplotlib's tab10 for up to 10 series, else viridis samples short of its faint yellow end."""
    if n <= 10:
        return [plt.get_cmap("tab10")(i) for i in range(n)]
    return [plt.get_cmap("viridis")(0.9 * i / (n - 1)) for i in range(n)]


def figure(args, xlabel, ylabel):
    """A figure of exactly --width x --height pixels with one set of axes."""
    dpi = 100
    fig, ax = plt.subplots(figsize=(args.width / dpi, args.height / dpi), dpi=dpi, layout="constrained")
    ax.set_title(args.title)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.grid(True, color="0.9")
    ax.set_axisbelow(True)
    return fig, ax


def save(fig, out):
    """Writes beside the target, then renames, so a failed run leaves no half-written figure."""
    root, extension = os.path.splitext(out)
    tmp = f"{root}.tmp-{os.getpid()}{extension}"
    try:
        fig.savefig(tmp, dpi=fig.dpi)
        os.replace(tmp, out)
    except OSError as e:
        if os.path.exists(tmp):
            os.remove(tmp)
        raise FigureError(f"{out}: {e.strerror}")
    finally:
        plt.close(fig)


def run(draw, args):
    """Calls draw(args); a FigureError or ValueError ends the script with one line on stderr."""
    try:
        draw(args)
    except (FigureError, ValueError) as e:
        sys.exit(f"{os.path.basename(sys.argv[0])}: error: {e}")
