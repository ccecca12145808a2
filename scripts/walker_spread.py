#!/usr/bin/env python3
"""The spread of the walker's headline figures over evaluation seeds (docs/results.md, "Figure 4").

The Figure 4 evaluation and the transition experiment from the demonstrations' own starts (RESULTS_DIR/eval,
RESULTS_DIR/transitions: the published figures) beside the same evaluations from fresh starts, one per evaluation
seed (RESULTS_DIR/spread/seedN/{eval,transitions}, `--start-seed N`; scripts/reproduce/walker.sh spread writes
them all), as Markdown tables on standard output: per figure its value from the own starts, from each seed, and
the mean and range (min-max) of them all. Reads the rows (imitation.csv, transitions.csv), runs nothing.

Usage: scripts/walker_spread.py [RESULTS_DIR]   (default results/walker)
"""
import csv
import os
import re
import statistics
import sys


def rows(path):
    if not os.path.isfile(path):
        sys.exit(f"{sys.argv[0]}: no {path} (run scripts/reproduce/walker.sh spread)")
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def in_order(items):
    return list(dict.fromkeys(items))


def imitation_figures(path):
    """(policy, demonstrations) -> {median |dspeed|, falls %} as eval walker's summary.md computes them."""
    out = {}
    table = rows(path)
    for policy in in_order(r["policy"] for r in table):
        for held_out, label in (("0", "training experts"), ("1", "held-out experts (one-shot)")):
            group = [r for r in table if r["policy"] == policy and r["held_out"] == held_out]
            if group:
                out[policy, label] = (statistics.median(float(r["abs_diff"]) for r in group),
                                      100.0 * sum(r["fell"] == "1" for r in group) / len(group))
    return out


def transition_figures(path):
    """(policy, transition) -> {stayed up %, matched B %} as eval transitions' summary.md computes them."""
    out = {}
    table = rows(path)
    for policy in in_order(r["policy"] for r in table):
        for reference, label in ((False, "A, B of different speeds"), (True, "none: B from B's start (reference)")):
            group = [r for r in table
                     if r["policy"] == policy and (r["from_episode"] == r["to_episode"]) == reference]
            if group:
                out[policy, label] = (100.0 * sum(r["fell"] == "0" for r in group) / len(group),
                                      100.0 * sum(r["matched"] == "1" for r in group) / len(group))
    return out


def table(keys, titles, runs, seeds):
    """runs: [{key: (value, ...)}], the own starts first; titles: (title, format) per value."""
    head = "| " + " | ".join(keys) + " |"
    rule = "|" + "---|" * len(keys)
    for title, _ in titles:
        head += f" {title}: own starts | start seeds {', '.join(seeds)} | mean (min–max) |"
        rule += "---:|---:|---:|"
    lines = [head, rule]
    for key in runs[0]:
        line = "| " + " | ".join(key) + " |"
        for i, (_, fmt) in enumerate(titles):
            values = [run[key][i] for run in runs]
            line += (f" {fmt(values[0])} | {', '.join(fmt(v) for v in values[1:])} |"
                     f" {fmt(statistics.mean(values))} ({fmt(min(values))}–{fmt(max(values))}) |")
        lines.append(line)
    return "\n".join(lines)


def main():
    results = sys.argv[1] if len(sys.argv) > 1 else "results/walker"
    spread = os.path.join(results, "spread")
    seeds = sorted((m.group(1) for m in (re.fullmatch(r"seed(\d+)", d) for d in
                                         (os.listdir(spread) if os.path.isdir(spread) else [])) if m), key=int)
    if not seeds:
        sys.exit(f"{sys.argv[0]}: no {spread}/seed*/ (run scripts/reproduce/walker.sh spread)")
    dirs = [results] + [os.path.join(spread, "seed" + s) for s in seeds]
    speed = lambda v: f"{v:.3f}"  # noqa: E731
    percent = lambda v: f"{v:.1f}%"  # noqa: E731
    n = len(dirs)
    print(f"Figure 4 evaluation (eval walker): from the demonstrations' own starts and from fresh starts, start seeds "
          f"{', '.join(seeds)}; mean and range over the {n}.\n")
    print(table(("policy", "demonstrations"), (("median \\|Δspeed\\| (m/s)", speed), ("falls", percent)),
                [imitation_figures(os.path.join(d, "eval", "imitation.csv")) for d in dirs], seeds))
    print(f"\nTransitions (eval transitions, the same 200 pairs and 145 references): from A's (or B's) own start and "
          f"from fresh starts, start seeds {', '.join(seeds)}; mean and range over the {n}.\n")
    print(table(("policy", "transition"), (("stayed up", percent), ("matched B", percent)),
                [transition_figures(os.path.join(d, "transitions", "transitions.csv")) for d in dirs], seeds))


if __name__ == "__main__":
    main()
