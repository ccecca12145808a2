// Demonstrations to and from the layouts of other tools:
//   Minari   a dataset directory: metadata.json + main_data.hdf5 with groups episode_{i} holding
//            observations [T+1, D], actions [T, A], rewards, terminations, truncations [T]
//            (Box spaces; Dict, Tuple, Discrete and Text spaces are refused by name)
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

// A directory that export_minari wrote reads back whole (features, context, body and all).
DemoSet import_minari(const std::string& dir);
DemoSet import_imitation_npz(const std::string& path);

// Renames the set's components after `env`, attaches its control step, context names and body,
// and records `env.id()`; throws DataError when the dimensions differ. Features stay as imported.
void adopt_env(DemoSet& set, const Env& env);

// Writes DIR/main_data.hdf5 (the demonstration layout, which Minari's reader reads) and
// DIR/metadata.json (dataset_id, total_episodes, total_steps, data_format, minari_version, the
// observation and action spaces as Minari serialises them, and the body's MJCF text), into a
// temporary directory renamed to DIR at the end: DIR appears whole or not at all. Throws when
// DIR exists, unless `replace`.
void export_minari(const DemoSet& set, const std::string& dir, const std::string& dataset_id, bool replace = false);

// The minari_version export_minari records: the first release with data_format in metadata.json.
inline const char* const kMinariVersion = "0.5.0";

}  // namespace vaegail
