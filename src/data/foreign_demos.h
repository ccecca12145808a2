// Demonstrations to and from the layouts of other tools:
//   Minari   a dataset directory DATASET/data/ holding metadata.json + main_data.hdf5, whose groups
//            episode_{i} hold observations [T+1, D], actions [T, A], rewards, terminations,
//            truncations [T] (Box spaces; Dict, Tuple, Discrete and Text spaces are refused by
//            name). Minari keeps dataset ID in ROOT/ID/ (an ID may hold slashes: D4RL/door/human-v2),
//            ROOT being $MINARI_DATASETS_PATH, else ~/.minari/datasets (its "Dataset Standards").
//   imitation an .npz of its trajectories: obs [sum(T_i + 1), D], acts [sum T_i, A],
//            indices [n - 1] (where each trajectory's actions start), terminal [n], rews
//            (optional) and infos (pickled dicts: skipped)
// Imported episodes name their components obs_0..., act_0... and carry no features, context or
// body until adopt_env() gives them an environment's.
#pragma once

#include <string>

#include "data/demos.h"
#include "env/env.h"

namespace vaegail {

// The folder holding a Minari dataset's metadata.json and main_data.hdf5, for `source` taken as
// (in this order) a dataset directory (SOURCE/data/), its data folder (SOURCE/) or a dataset ID
// (minari_datasets_root()/SOURCE/data/). None holding metadata.json throws DataError naming
// every place looked in.
std::string minari_data_dir(const std::string& source);
// Where Minari keeps its datasets: $MINARI_DATASETS_PATH, else ~/.minari/datasets; empty when
// neither the variable nor HOME is set.
std::string minari_datasets_root();

// A Minari dataset named as minari_data_dir takes it. A directory that export_minari wrote reads
// back whole (features, context, body and all).
DemoSet import_minari(const std::string& source);
DemoSet import_imitation_npz(const std::string& path);

// Renames the set's components after `env`, attaches its control step, context names and body,
// and records `env.id()`; throws DataError when the dimensions differ. Features stay as imported.
void adopt_env(DemoSet& set, const Env& env);

// Writes DIR/data/main_data.hdf5 (the demonstration layout, which Minari's reader reads) and
// DIR/data/metadata.json (dataset_id, total_episodes, total_steps, data_format, minari_version, the
// observation and action spaces as Minari serialises them, and the body's MJCF text): Minari's
// layout, so DIR = minari_datasets_root()/ID is what minari.load_dataset(ID) reads. It goes into a
// temporary directory renamed to DIR at the end: DIR appears whole or not at all. Throws when
// DIR exists, unless `replace`.
void export_minari(const DemoSet& set, const std::string& dir, const std::string& dataset_id, bool replace = false);

// The minari_version export_minari records: the first release with data_format in metadata.json.
inline const char* const kMinariVersion = "0.5.0";

}  // namespace vaegail
