#!/usr/bin/env python3
"""Writes the demonstration tests' toy file the way a Python user would with h5py (defaults:
contiguous datasets, variable-length string attributes; one dataset gzip-chunked; an extra
group), so the suite checks that the reader keeps loading files this program did not write.
The values are those of src/data/demos_test_support.h's toy_file_episode: keep the two in step.
Usage: write_h5py_demos.py OUT.h5"""
import json
import sys

import h5py
import numpy as np


def toy_episode(T, offset):
    t = np.arange(T + 1)
    obs = np.stack([offset + t, -offset * t], axis=1).astype(np.float32)
    steps = np.arange(T)
    return {
        "observations": obs,
        "actions": (0.5 * steps).astype(np.float32).reshape(T, 1),
        "rewards": 1.0 / (steps + 1),
        "terminations": (steps == T - 1) & (offset > 1),
        "truncations": (steps == T - 1) & (offset <= 1),
        "speed": 0.1 * t + offset,
        "expert_id": "expert_%d" % offset,
        "context": np.array([offset], dtype=np.float64),
        "achieved_speed": offset * 0.5,
    }


with h5py.File(sys.argv[1], "w") as f:
    episodes = [toy_episode(5, 1), toy_episode(3, 2)]
    f.attrs["format"] = "vaegail-demos"
    f.attrs["format_version"] = np.int64(1)
    f.attrs["total_episodes"] = np.int64(len(episodes))
    f.attrs["total_steps"] = np.int64(sum(len(e["rewards"]) for e in episodes))
    f.attrs["env_id"] = "toy"
    f.attrs["control_timestep"] = 0.025
    for key, names in [("observation_names", ["x", "v"]), ("action_names", ["f"]),
                       ("feature_names", ["speed"]), ("context_names", ["target_speed"])]:
        f.attrs[key] = json.dumps(names)
    f.create_group("extras").create_dataset("notes", data=np.arange(3.0))
    for i, e in enumerate(episodes):
        g = f.create_group("episode_%d" % i)
        g.create_dataset("observations", data=e["observations"])
        g.create_dataset("actions", data=e["actions"], compression="gzip", chunks=True)
        for key in ["rewards", "terminations", "truncations"]:
            g.create_dataset(key, data=e[key])
        g.create_group("features").create_dataset("speed", data=e["speed"])
        g.attrs["id"] = np.int64(i)
        g.attrs["total_steps"] = np.int64(len(e["rewards"]))
        g.attrs["seed"] = np.uint64(0xFFFFFFFFFFFFFFF1)
        g.attrs["expert_id"] = e["expert_id"]
        g.attrs["context"] = e["context"]
        g.attrs["achieved_speed"] = e["achieved_speed"]
