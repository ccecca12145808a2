#!/usr/bin/env python3
"""Writes one episode's observations from a demonstration file (vaegail's or Minari's HDF5
layout: /episode_{i}/observations [T+1, obs_dim]) as the text walker_controller reads: a '#'
header, then one observation per line.

    python3 demo_states.py data/walker/demos.h5 42 > demo.txt
"""
import sys

import h5py


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    path, episode = sys.argv[1], int(sys.argv[2])
    with h5py.File(path, "r") as f:
        group = f[f"episode_{episode}"]
        states = group["observations"][()]
        attrs = {k: group.attrs[k] for k in ("expert_id", "context", "mean_com_speed") if k in group.attrs}
    print(f"# {path} episode {episode}: {states.shape[0]} states x {states.shape[1]}; {attrs}")
    for row in states:
        print(" ".join(f"{x:.6g}" for x in row))


if __name__ == "__main__":
    main()
