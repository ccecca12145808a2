#!/usr/bin/env python3
"""Fixtures in the layouts of other tools, written as those tools write them (h5py and numpy
directly, not this project's writer), and a check of an exported directory as Minari reads it.
The values follow simple formulas that src/data/foreign_demos_test.cpp checks: keep the two in step.
Usage: write_foreign_demos.py minari|minari_dict|npz|check_minari PATH"""
import json
import sys

import h5py
import numpy as np

MINARI_LENGTHS = [4, 2]
NPZ_LENGTHS = [4, 2, 3]


def minari_obs(ep, T):
    # float64, as gymnasium's MuJoCo environments observe: value ep*10 + t + 0.1*k
    return ep * 10 + np.arange(T + 1)[:, None] + 0.1 * np.arange(3)[None, :]


def write_minari(dataset_dir, dict_space=False):
    """As Minari lays a dataset out: DATASET/data/{metadata.json, main_data.hdf5}."""
    import os
    path = os.path.join(dataset_dir, "data")
    os.makedirs(path, exist_ok=True)
    inf_box = lambda n, dtype: json.dumps({"type": "Box", "dtype": dtype, "shape": [n],
                                           "low": [-np.inf] * n, "high": [np.inf] * n})
    obs_space = inf_box(3, "float64")
    if dict_space:
        obs_space = json.dumps({"type": "Dict", "subspaces": {"joints": json.loads(inf_box(3, "float64"))}})
    metadata = {
        "total_episodes": len(MINARI_LENGTHS), "total_steps": sum(MINARI_LENGTHS), "data_format": "hdf5",
        "observation_space": obs_space, "action_space": json.dumps({"type": "Box", "dtype": "float32", "shape": [2],
                                                                    "low": [-1.0, -1.0], "high": [1.0, 1.0]}),
        "env_spec": json.dumps({"id": "TinyHopper-v0", "entry_point": None, "max_episode_steps": 50}),
        "dataset_id": "tiny/expert-v0", "minari_version": "0.5.1", "author": "fixture",
    }
    with open(os.path.join(path, "metadata.json"), "w") as f:
        json.dump(metadata, f)
    with h5py.File(os.path.join(path, "main_data.hdf5"), "w", track_order=True) as f:
        for ep, T in enumerate(MINARI_LENGTHS):
            g = f.create_group("episode_%d" % ep)
            g.attrs["id"] = ep
            g.attrs["seed"] = 42 + ep
            g.attrs["total_steps"] = T
            if dict_space:
                g.create_group("observations").create_dataset("joints", data=minari_obs(ep, T))
            else:
                g.create_dataset("observations", data=minari_obs(ep, T), chunks=True, maxshape=(None, 3))
            acts = (0.5 * np.arange(T)[:, None] - np.arange(2)[None, :] + ep).astype(np.float32)
            g.create_dataset("actions", data=acts, chunks=True, maxshape=(None, 2))
            g.create_dataset("rewards", data=np.arange(T) * 0.25 + ep, chunks=True, maxshape=(None,))
            g.create_dataset("terminations", data=np.arange(T) == T - 1 if ep == 0 else np.zeros(T, bool))
            g.create_dataset("truncations", data=np.arange(T) == T - 1 if ep == 1 else np.zeros(T, bool))
            g.create_group("infos").create_dataset("success", data=np.zeros(T + 1, bool))


def write_npz(path):
    # imitation's types.save layout: trajectories concatenated, split by `indices`.
    obs, acts, rews = [], [], []
    for i, T in enumerate(NPZ_LENGTHS):
        obs.append(i * 100 + np.arange(T + 1, dtype=np.float32)[:, None] * np.array([1, -1], np.float32))
        acts.append((i + 0.5 * np.arange(T, dtype=np.float32))[:, None])
        rews.append(np.full(T, float(i)))
    infos = np.array([{"step": k} for k in range(sum(NPZ_LENGTHS))], dtype=object)
    np.savez_compressed(path, obs=np.concatenate(obs), acts=np.concatenate(acts), infos=infos,
                        terminal=np.array([True, False, True]), rews=np.concatenate(rews),
                        indices=np.cumsum(NPZ_LENGTHS[:-1]))


def check_minari(dataset_dir):
    """What Minari's MinariStorage.read and HDF5Storage.get_episodes rely on, in the dataset
    directory's data folder (minari.load_dataset reads ROOT/ID/data)."""
    import os
    path = os.path.join(dataset_dir, "data")
    with open(os.path.join(path, "metadata.json")) as f:
        metadata = json.load(f)
    for key in ["dataset_id", "total_episodes", "total_steps", "data_format", "minari_version",
                "observation_space", "action_space"]:
        assert key in metadata, key
    assert metadata["data_format"] == "hdf5"
    spaces = {}
    for key in ["observation_space", "action_space"]:
        assert isinstance(metadata[key], str), key  # serialised twice, as serialize_space does
        space = json.loads(metadata[key])
        assert space["type"] == "Box" and len(space["low"]) == space["shape"][0] == len(space["high"]), key
        np.dtype(space["dtype"])
        spaces[key] = space
    steps = 0
    with h5py.File(os.path.join(path, "main_data.hdf5"), "r") as f:
        for ep in range(metadata["total_episodes"]):
            g = f["episode_%d" % ep]
            obs, acts = g["observations"][()], g["actions"][()]
            T = len(g["rewards"][:])
            assert obs.shape == (T + 1, spaces["observation_space"]["shape"][0]), obs.shape
            assert acts.shape == (T, spaces["action_space"]["shape"][0]), acts.shape
            assert g["terminations"][:].dtype == bool and g["truncations"][:].shape == (T,)
            assert int(g.attrs["seed"]) >= 0 and int(g.attrs["total_steps"]) == T
            steps += T
    assert steps == metadata["total_steps"], (steps, metadata["total_steps"])
    print("minari layout ok: %d episodes, %d steps" % (metadata["total_episodes"], steps))


if __name__ == "__main__":
    mode, path = sys.argv[1], sys.argv[2]
    {"minari": write_minari, "minari_dict": lambda p: write_minari(p, dict_space=True), "npz": write_npz,
     "check_minari": check_minari}[mode](path)
