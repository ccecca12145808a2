#include "data/foreign_demos.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "data/hdf5_handle.h"
#include "data/npy.h"
#include "util/atomic_file.h"
#include "util/sha256.h"
#include "util/zip_check.h"

namespace vaegail {

namespace fs = std::filesystem;

namespace {

const char* const kMainFile = "main_data.hdf5";
const char* const kMetadataFile = "metadata.json";
const char* const kDataFolder = "data";  // a dataset directory's folder of files

std::vector<std::string> numbered(const std::string& prefix, int n) {
  std::vector<std::string> names;
  for (int i = 0; i < n; ++i) names.push_back(prefix + std::to_string(i));
  return names;
}

DemoHeader imported_header(const std::string& env_id, int obs_dim, int act_dim) {
  DemoHeader h;
  h.env_id = env_id;
  h.observation_names = numbered("obs_", obs_dim);
  h.action_names = numbered("act_", act_dim);
  return h;
}

// Python's json writes infinite bounds as Infinity, which strict JSON parsers refuse: read them
// as the largest doubles (the bounds are not used, only the space's type).
nlohmann::json parse_python_json(std::string text, const std::string& where) {
  for (size_t at = 0; (at = text.find("Infinity", at)) != std::string::npos;) text.replace(at, 8, "1e308");
  for (size_t at = 0; (at = text.find("NaN", at)) != std::string::npos;) text.replace(at, 3, "null");
  try {
    return nlohmann::json::parse(text);
  } catch (const std::exception&) {
    throw DataError(where + ": not valid JSON");
  }
}

// The space's type must be Box: everything else is named in the refusal.
void require_box(const nlohmann::json& metadata, const std::string& key, const std::string& where) {
  if (!metadata.contains(key)) return;
  const auto& value = metadata[key];
  const auto space = value.is_string() ? parse_python_json(value.get<std::string>(), where + ": " + key) : value;
  const std::string type = space.value("type", "?");
  if (type != "Box")
    throw DataError(where + ": " + key + " is a " + type + " space: only Box (flat, continuous) spaces are read");
}

std::string minari_env_id(const nlohmann::json& metadata, const std::string& where) {
  if (metadata.contains("env_spec") && metadata["env_spec"].is_string()) {
    const auto spec = parse_python_json(metadata["env_spec"].get<std::string>(), where + ": env_spec");
    if (spec.contains("id") && spec["id"].is_string()) return spec["id"].get<std::string>();
  }
  return metadata.value("dataset_id", "minari");
}

Episode read_minari_episode(hid_t file, int index, DemoHeader& h, const std::string& path) {
  const std::string name = "episode_" + std::to_string(index), where = path + ": " + name;
  h5::require_link(file, name, where, "episode group");
  h5::Handle group(H5Gopen2(file, name.c_str(), H5P_DEFAULT), H5Gclose);
  if (!group.valid()) throw DataError(h5::with_cause(where + ": cannot open episode group"));
  const hid_t g = group.get();
  if (h5::has_link(g, "observations", where) &&
      H5Iget_type(h5::Handle(H5Oopen(g, "observations", H5P_DEFAULT), H5Oclose).get()) == H5I_GROUP)
    throw DataError(where + "/observations: a group (a Dict or Tuple space): only Box observations are read");
  const auto obs_dims = h5::dataset_dims(g, "observations", where), act_dims = h5::dataset_dims(g, "actions", where);
  if (obs_dims.empty() || obs_dims.size() > 2 || act_dims.empty() || act_dims.size() > 2 || obs_dims[0] < 1)
    throw DataError(where + ": observations " + h5::shape_text(obs_dims) + " and actions " + h5::shape_text(act_dims) +
                    ": expected [T+1, D] and [T, A]");
  const hsize_t T = act_dims[0];
  const hsize_t D = obs_dims.size() == 2 ? obs_dims[1] : 1, A = act_dims.size() == 2 ? act_dims[1] : 1;
  if (index == 0) h = imported_header(h.env_id, static_cast<int>(D), static_cast<int>(A));
  Episode e;
  h5::read_dataset(g, "observations", H5T_FLOAT, H5T_NATIVE_FLOAT, {T + 1, hsize_t(h.obs_dim())}, e.observations, where);
  h5::Handle actions(H5Dopen2(g, "actions", H5P_DEFAULT), H5Dclose);
  h5::Handle action_type(H5Dget_type(actions.get()), H5Tclose);
  if (H5Tget_class(action_type.get()) != H5T_FLOAT)
    throw DataError(where + "/actions: not floating point (a Discrete space?): only continuous actions are imitated");
  h5::read_dataset(g, "actions", H5T_FLOAT, H5T_NATIVE_FLOAT, act_dims, e.actions, where);
  if (act_dims.size() == 1 ? h.act_dim() != 1 : act_dims[1] != hsize_t(h.act_dim()))
    throw DataError(where + "/actions: shape " + h5::shape_text(act_dims) + ", episode_0's width is " +
                    std::to_string(h.act_dim()));
  h5::read_dataset(g, "rewards", H5T_FLOAT, H5T_NATIVE_DOUBLE, {T}, e.rewards, where);
  h5::read_dataset(g, "terminations", H5T_ENUM, H5T_NATIVE_UINT8, {T}, e.terminations, where);
  h5::read_dataset(g, "truncations", H5T_ENUM, H5T_NATIVE_UINT8, {T}, e.truncations, where);
  const auto attrs = h5::attr_names(g);
  if (std::find(attrs.begin(), attrs.end(), "seed") != attrs.end()) {
    h5::Handle seed(H5Aopen(g, "seed", H5P_DEFAULT), H5Aclose);
    if (H5Aread(seed.get(), H5T_NATIVE_UINT64, &e.seed) < 0) throw DataError(where + ": cannot read seed");
  } else {
    e.seed = static_cast<std::uint64_t>(index);
  }
  e.expert_id = "minari";
  validate_episode(e, h, where);
  return e;
}

void check_dims(const DemoSet& set, const Env& env) {
  if (set.header.obs_dim() != env.obs_dim() || set.header.act_dim() != env.act_dim())
    throw DataError(set.path + ": observations/actions of " + std::to_string(set.header.obs_dim()) + "/" +
                    std::to_string(set.header.act_dim()) + " components, task '" + env.id() + "' has " +
                    std::to_string(env.obs_dim()) + "/" + std::to_string(env.act_dim()));
}

nlohmann::json box_space(const BoxSpec& box) {
  return {{"type", "Box"}, {"dtype", "float32"}, {"shape", {box.dim()}}, {"low", box.low}, {"high", box.high}};
}

BoxSpec unbounded_box(int dim) {
  BoxSpec box;
  box.names.resize(dim);
  box.low.assign(dim, -3.4e38);  // float32's range: Minari's Box takes finite bounds as they are
  box.high.assign(dim, 3.4e38);
  return box;
}

}  // namespace

std::string minari_datasets_root() {
  const char* root = std::getenv("MINARI_DATASETS_PATH");
  if (root && *root) return root;
  const char* home = std::getenv("HOME");
  return home && *home ? (fs::path(home) / ".minari" / "datasets").string() : "";
}

std::string minari_data_dir(const std::string& source) {
  std::vector<fs::path> candidates = {fs::path(source) / kDataFolder, fs::path(source)};
  // An ID is a relative name under the root; an absolute path names a directory only.
  const std::string root = minari_datasets_root();
  if (!root.empty() && fs::path(source).is_relative())
    candidates.push_back(fs::path(root) / source / kDataFolder);
  std::string looked;
  for (const auto& dir : candidates) {
    if (fs::is_regular_file(dir / kMetadataFile)) return dir.lexically_normal().string();
    looked += (looked.empty() ? "" : ", ") + (dir / kMetadataFile).lexically_normal().string();
  }
  throw DataError(source + ": no Minari dataset (no " + looked + ")");
}

DemoSet import_minari(const std::string& source) {
  const std::string dir = minari_data_dir(source);
  const std::string meta_path = (fs::path(dir) / kMetadataFile).string(), main_path = (fs::path(dir) / kMainFile).string();
  const auto metadata = parse_python_json(read_file(meta_path), meta_path);
  const std::string format = metadata.value("data_format", "hdf5");
  if (format != "hdf5") throw DataError(meta_path + ": data_format '" + format + "': only hdf5 datasets are read");
  require_box(metadata, "observation_space", meta_path);
  require_box(metadata, "action_space", meta_path);
  if (!fs::exists(main_path)) throw DataError(dir + ": no " + kMainFile);
  h5::silence_errors();
  {
    // A directory export_minari wrote: its main file is a whole demonstration file.
    h5::Handle file(H5Fopen(main_path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
    if (!file.valid()) throw DataError(h5::with_cause(main_path + ": cannot open HDF5 file"));
    const auto attrs = h5::attr_names(file.get());
    if (std::find(attrs.begin(), attrs.end(), "format") != attrs.end()) {
      file.reset();
      DemoSet set = read_demos(main_path);
      set.header.body_mjcf = metadata.value("vaegail_body_mjcf", "");
      if (sha256_hex(set.header.body_mjcf) != metadata.value("vaegail_body_sha256", sha256_hex("")))
        throw DataError(meta_path + ": vaegail_body_mjcf fails its SHA-256");
      return set;
    }
  }
  h5::Handle file(H5Fopen(main_path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  const hid_t root = file.get();
  const double total = metadata.value("total_episodes", -1.0);
  if (!(total >= 1) || total != std::floor(total) || total > double(h5::link_count(root)))
    throw DataError(meta_path + ": total_episodes must count the episode groups of " + kMainFile);
  DemoSet set;
  set.path = dir;
  set.header.env_id = minari_env_id(metadata, meta_path);
  for (int i = 0; i < static_cast<int>(total); ++i)
    set.episodes.push_back(read_minari_episode(root, i, set.header, main_path));
  return set;
}

DemoSet import_imitation_npz(const std::string& path) {
  std::map<std::string, std::string> entries;
  try {
    entries = zip_entries(read_file(path));
  } catch (const std::exception& e) {
    throw DataError(names_in_one_line(e.what(), path) ? std::string(e.what()) : path + ": not a whole .npz archive: " + e.what());
  }
  const auto array = [&](const std::string& name, bool required) {
    const auto it = entries.find(name + ".npy");
    if (it == entries.end()) {
      if (required) throw DataError(path + ": no array '" + name + "' (an imitation trajectory file has obs, acts, indices, terminal)");
      return NpyArray{};
    }
    return parse_npy(it->second, path + ": " + name);
  };
  const NpyArray obs = array("obs", true), acts = array("acts", true), indices = array("indices", true),
                 terminal = array("terminal", true), rews = array("rews", false);
  const std::uint64_t n = terminal.values.size();
  if (n == 0 || indices.values.size() != n - 1)
    throw DataError(path + ": " + std::to_string(indices.values.size()) + " indices for " + std::to_string(n) +
                    " trajectories (expected one fewer)");
  if (obs.rows() != acts.rows() + n)
    throw DataError(path + ": " + std::to_string(obs.rows()) + " observations for " + std::to_string(acts.rows()) +
                    " actions in " + std::to_string(n) + " trajectories (expected one more per trajectory)");
  if (!rews.shape.empty() && rews.values.size() != acts.rows())
    throw DataError(path + ": " + std::to_string(rews.values.size()) + " rewards for " + std::to_string(acts.rows()) + " actions");
  DemoSet set;
  set.path = path;
  set.header = imported_header("imitation", static_cast<int>(obs.row_width()), static_cast<int>(acts.row_width()));
  const std::uint64_t D = obs.row_width(), A = acts.row_width();
  std::uint64_t begin = 0;
  for (std::uint64_t i = 0; i < n; ++i) {
    const std::uint64_t end = i + 1 < n ? static_cast<std::uint64_t>(indices.values[i]) : acts.rows();
    if (end <= begin || end > acts.rows())
      throw DataError(path + ": indices must rise strictly within the " + std::to_string(acts.rows()) + " actions");
    Episode e;
    // Trajectory i's observations start after the i final observations of those before it.
    e.observations.assign(obs.values.begin() + (begin + i) * D, obs.values.begin() + (end + i + 1) * D);
    e.actions.assign(acts.values.begin() + begin * A, acts.values.begin() + end * A);
    e.rewards = rews.shape.empty() ? std::vector<double>(end - begin, 0.0)
                                   : std::vector<double>(rews.values.begin() + begin, rews.values.begin() + end);
    e.terminations.assign(end - begin, 0);
    e.truncations.assign(end - begin, 0);
    (terminal.values[i] != 0 ? e.terminations : e.truncations).back() = 1;
    e.expert_id = "imitation";
    e.seed = i;
    validate_episode(e, set.header, path + ": trajectory " + std::to_string(i));
    set.episodes.push_back(std::move(e));
    begin = end;
  }
  return set;
}

void adopt_env(DemoSet& set, const Env& env) {
  check_dims(set, env);
  DemoHeader& h = set.header;
  h.env_id = env.id();
  h.control_timestep = env.control_timestep();
  h.observation_names = env.observation_spec().names;
  h.action_names = env.action_spec().names;
  h.body_mjcf = env.body_mjcf();
  h.context_names = env.context_names();
  for (auto& e : set.episodes)
    if (e.context.size() != h.context_names.size()) e.context = env.context();
}

void export_minari(const DemoSet& set, const std::string& dir, const std::string& dataset_id, bool replace) {
  const fs::path target = fs::path(dir).lexically_normal();
  if (fs::exists(target) && !replace) throw std::runtime_error(dir + ": exists (pass --force to replace it)");
  const fs::path tmp = fresh_temporary_path(target.string());
  const fs::path tmp_data = tmp / kDataFolder;
  fs::remove_all(tmp);
  try {
    fs::create_directories(tmp_data);
    DemoHeader header = set.header;
    header.body_mjcf.clear();  // in metadata.json: Minari counts the main file's groups as episodes
    DemoWriter writer((tmp_data / kMainFile).string(), header);
    std::int64_t steps = 0;
    for (const auto& e : set.episodes) {
      writer.append(e);
      steps += e.length();
    }
    writer.commit();
    BoxSpec obs = unbounded_box(header.obs_dim()), act = unbounded_box(header.act_dim());
    const nlohmann::json metadata = {
        {"dataset_id", dataset_id},
        {"total_episodes", set.episodes.size()},
        {"total_steps", steps},
        {"data_format", "hdf5"},
        {"minari_version", kMinariVersion},
        {"observation_space", box_space(obs).dump()},
        {"action_space", box_space(act).dump()},
        {"vaegail_env_id", header.env_id},
        {"vaegail_body_mjcf", set.header.body_mjcf},
        {"vaegail_body_sha256", sha256_hex(set.header.body_mjcf)}};
    write_file_atomically((tmp_data / kMetadataFile).string(), metadata.dump(2) + "\n");
    const fs::path previous = target.string() + ".old-" + std::to_string(::getpid());
    if (fs::exists(target)) fs::rename(target, previous);
    fs::rename(tmp, target);
    fs::remove_all(previous);
  } catch (const fs::filesystem_error& e) {
    fs::remove_all(tmp);
    throw std::runtime_error(dir + ": " + e.code().message());
  } catch (...) {
    fs::remove_all(tmp);
    throw;
  }
}

}  // namespace vaegail
