// Demonstration trajectories on HDF5, in the layout Minari uses so h5py users read plain arrays.
//
// File layout (format "vaegail-demos", version 1):
//   /                       attrs: format, format_version, env_id, control_timestep,
//                                  observation_names, action_names, feature_names,
//                                  context_names (JSON lists as UTF-8 strings),
//                                  total_episodes, total_steps;
//                                  body_sha256 (hex) when the file has a body_mjcf
//   /body_mjcf                  uint8 [n]  the MJCF text of a user's body (GenericTaskEnv), so
//                               that later stages rebuild its environment from the file alone;
//                               absent for built-in tasks and in files of other tools
//   /episode_{i}/observations   float32 [T+1, obs_dim]
//   /episode_{i}/actions        float32 [T, act_dim]
//   /episode_{i}/rewards        float64 [T]
//   /episode_{i}/terminations   bool    [T]  (h5py's enum of int8 FALSE/TRUE)
//   /episode_{i}/truncations    bool    [T]
//   /episode_{i}/features/{name} float64 [T+1]  one per feature, aligned with observations
//   /episode_{i}            attrs: id, total_steps, expert_id, context (float64 [k]), seed,
//                                  plus any extra float64 scalars (achieved_speed, held_out...)
// Written in the HDF5 1.10 file format (checksummed metadata); every dataset is one chunk,
// shuffled, deflated and Fletcher-32 checksummed; strings are fixed-length. A flipped byte
// anywhere the checksums cover is rejected on reading rather than loaded.
#pragma once

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace vaegail {

constexpr int kDemoFormatVersion = 1;

// Every reading or validation problem: one line naming the file, the episode and the field.
class DataError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct DemoHeader {
  std::string env_id;
  double control_timestep = 0.0;
  std::vector<std::string> observation_names, action_names, feature_names, context_names;
  std::string body_mjcf;  // empty: the task is built in (env_id names it)
  int obs_dim() const { return static_cast<int>(observation_names.size()); }
  int act_dim() const { return static_cast<int>(action_names.size()); }
};

struct Episode {
  std::vector<float> observations;          // [T+1, obs_dim]
  std::vector<float> actions;               // [T, act_dim]
  std::vector<double> rewards;              // [T]
  std::vector<std::uint8_t> terminations;   // [T], 0/1
  std::vector<std::uint8_t> truncations;    // [T], 0/1
  std::vector<double> features;             // [T+1, n_features], row-major
  std::string expert_id;
  std::vector<double> context;              // [n_context]
  std::uint64_t seed = 0;
  std::map<std::string, double> attributes; // extra per-episode scalars
  int length() const { return static_cast<int>(rewards.size()); }
  // Mean over steps 1..T of feature column f (the state each action led to).
  double mean_feature(int f, int n_features) const;
};

struct DemoSet {
  std::string path;
  DemoHeader header;
  std::vector<Episode> episodes;
};

// Builds the file in memory (HDF5's core driver); commit() writes its bytes to `path` atomically
// (util/atomic_file.h). Destroying an uncommitted writer (an exception, a kill) leaves `path` as
// it was and nothing beside it; so does a write that fails (a full disk), whose error is one line
// naming `path` and the cause. HDF5 never writes a disk itself: a full disk inside HDF5 left a
// file it could not close, and its library crashed at exit closing it again.
class DemoWriter {
 public:
  DemoWriter(std::string path, DemoHeader header);
  ~DemoWriter();
  DemoWriter(const DemoWriter&) = delete;
  DemoWriter& operator=(const DemoWriter&) = delete;

  // Throws DataError if the episode does not match the header or holds NaN/Inf.
  void append(const Episode& episode);
  void commit();
  int episodes_written() const { return episodes_; }

 private:
  void close_file();

  std::string path_;
  DemoHeader header_;
  std::int64_t file_ = -1;
  int episodes_ = 0;
  std::int64_t steps_ = 0;
};

// Checks an episode against a header; throws DataError "where: field: problem".
void validate_episode(const Episode& episode, const DemoHeader& header, const std::string& where);

// Reads and validates a whole file. Throws DataError on anything missing, malformed or failing
// a checksum (body_mjcf against body_sha256 too); sizes are checked before anything is allocated for them. Files of other tools
// (h5py: contiguous or chunked, gzip, extra groups, variable-length strings) read as well.
DemoSet read_demos(const std::string& path);

}  // namespace vaegail
