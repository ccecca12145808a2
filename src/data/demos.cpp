#include "data/demos.h"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "data/hdf5_handle.h"
#include "util/atomic_file.h"
#include "util/sha256.h"

namespace vaegail {

namespace {

const char* const kFormat = "vaegail-demos";
const char* const kBody = "body_mjcf";
// Attributes every episode carries; anything else numeric is an extra attribute.
const char* const kEpisodeAttrs[] = {"id", "total_steps", "expert_id", "context", "seed"};

template <typename T>
void check_finite(const std::vector<T>& values, size_t row_width, const std::string& where) {
  for (size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(static_cast<double>(values[i])))
      throw DataError(where + ": non-finite value " + std::to_string(values[i]) + " at row " +
                      std::to_string(i / row_width) + ", column " + std::to_string(i % row_width));
}

template <typename T>
void check_size(const std::vector<T>& values, size_t expected, const std::string& where,
                const std::string& shape) {
  if (values.size() != expected)
    throw DataError(where + ": " + std::to_string(values.size()) + " values, expected " + shape);
}

std::string json_list(const std::vector<std::string>& names) { return nlohmann::json(names).dump(); }

std::vector<std::string> parse_list(const std::string& text, const std::string& where) {
  try {
    return nlohmann::json::parse(text).get<std::vector<std::string>>();
  } catch (const std::exception&) {
    throw DataError(where + ": not a JSON list of names");
  }
}

}  // namespace

double Episode::mean_feature(int f, int n_features) const {
  const int t_len = length();
  if (t_len == 0) return features.empty() ? 0.0 : features[f];
  double sum = 0;
  for (int t = 1; t <= t_len; ++t) sum += features[static_cast<size_t>(t) * n_features + f];
  return sum / t_len;
}

void validate_episode(const Episode& e, const DemoHeader& h, const std::string& where) {
  const size_t T = e.rewards.size();
  const std::string t = std::to_string(T);
  check_size(e.observations, (T + 1) * h.obs_dim(), where + "/observations",
             "[" + std::to_string(T + 1) + ", " + std::to_string(h.obs_dim()) + "] (T+1 rows for T = " + t + " rewards)");
  check_size(e.actions, T * h.act_dim(), where + "/actions", "[" + t + ", " + std::to_string(h.act_dim()) + "]");
  check_size(e.terminations, T, where + "/terminations", "[" + t + "]");
  check_size(e.truncations, T, where + "/truncations", "[" + t + "]");
  const size_t nf = h.feature_names.size();
  check_size(e.features, (T + 1) * nf, where + "/features",
             "[" + std::to_string(T + 1) + ", " + std::to_string(nf) + "]");
  check_size(e.context, h.context_names.size(), where + "/context", std::to_string(h.context_names.size()));
  check_finite(e.observations, h.obs_dim(), where + "/observations");
  check_finite(e.actions, h.act_dim(), where + "/actions");
  check_finite(e.rewards, 1, where + "/rewards");
  check_finite(e.features, nf ? nf : 1, where + "/features");
  check_finite(e.context, 1, where + "/context");
}

DemoWriter::DemoWriter(std::string path, DemoHeader header) : path_(std::move(path)), header_(std::move(header)) {
  h5::silence_errors();
  file_ = h5::create_file_in_memory(temporary_path_for(path_), path_).release();
}

DemoWriter::~DemoWriter() { close_file(); }

void DemoWriter::close_file() {
  if (file_ >= 0) H5Fclose(file_);
  file_ = -1;
}

void DemoWriter::append(const Episode& e) {
  const std::string name = "episode_" + std::to_string(episodes_);
  validate_episode(e, header_, path_ + ": " + name);
  const std::string where = path_ + ": " + name;
  const h5::Handle group = h5::create_group(file_, name, where);
  const hsize_t T = e.rewards.size();
  const hid_t g = group.get();
  h5::write_dataset(g, "observations", H5T_NATIVE_FLOAT, H5T_IEEE_F32LE,
                    {T + 1, static_cast<hsize_t>(header_.obs_dim())}, e.observations.data(), where);
  h5::write_dataset(g, "actions", H5T_NATIVE_FLOAT, H5T_IEEE_F32LE,
                    {T, static_cast<hsize_t>(header_.act_dim())}, e.actions.data(), where);
  h5::write_dataset(g, "rewards", H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, {T}, e.rewards.data(), where);
  h5::Handle boolean = h5::bool_type();
  h5::write_dataset(g, "terminations", boolean.get(), boolean.get(), {T}, e.terminations.data(), where);
  h5::write_dataset(g, "truncations", boolean.get(), boolean.get(), {T}, e.truncations.data(), where);
  const h5::Handle features = h5::create_group(g, "features", where);
  const size_t nf = header_.feature_names.size();
  std::vector<double> column(T + 1);
  for (size_t f = 0; f < nf; ++f) {
    for (size_t t = 0; t <= T; ++t) column[t] = e.features[t * nf + f];
    h5::write_dataset(features.get(), header_.feature_names[f], H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE,
                      {T + 1}, column.data(), where + "/features");
  }
  const long long id = episodes_, steps = static_cast<long long>(T);
  h5::write_scalar_attr(g, "id", H5T_NATIVE_LLONG, H5T_STD_I64LE, &id);
  h5::write_scalar_attr(g, "total_steps", H5T_NATIVE_LLONG, H5T_STD_I64LE, &steps);
  h5::write_scalar_attr(g, "seed", H5T_NATIVE_UINT64, H5T_STD_U64LE, &e.seed);
  h5::write_string_attr(g, "expert_id", e.expert_id);
  h5::write_double_attr(g, "context", e.context);
  for (const auto& [key, value] : e.attributes) h5::write_double_attr(g, key, {value});
  ++episodes_;
  steps_ += static_cast<std::int64_t>(T);
}

void DemoWriter::commit() {
  const hid_t root = file_;
  h5::write_string_attr(root, "format", kFormat);
  const long long version = kDemoFormatVersion, episodes = episodes_, steps = steps_;
  h5::write_scalar_attr(root, "format_version", H5T_NATIVE_LLONG, H5T_STD_I64LE, &version);
  h5::write_scalar_attr(root, "total_episodes", H5T_NATIVE_LLONG, H5T_STD_I64LE, &episodes);
  h5::write_scalar_attr(root, "total_steps", H5T_NATIVE_LLONG, H5T_STD_I64LE, &steps);
  h5::write_string_attr(root, "env_id", header_.env_id);
  h5::write_double_attr(root, "control_timestep", {header_.control_timestep});
  h5::write_string_attr(root, "observation_names", json_list(header_.observation_names));
  h5::write_string_attr(root, "action_names", json_list(header_.action_names));
  h5::write_string_attr(root, "feature_names", json_list(header_.feature_names));
  h5::write_string_attr(root, "context_names", json_list(header_.context_names));
  if (!header_.body_mjcf.empty()) {
    h5::write_dataset(root, kBody, H5T_NATIVE_UINT8, H5T_STD_U8LE, {header_.body_mjcf.size()},
                      header_.body_mjcf.data(), path_);
    h5::write_string_attr(root, "body_sha256", sha256_hex(header_.body_mjcf));
  }
  const std::string image = h5::file_image(file_, path_);
  close_file();
  write_file_atomically(path_, image);
}

namespace {

Episode read_episode(hid_t file, int index, const DemoHeader& h, const std::string& path) {
  const std::string name = "episode_" + std::to_string(index);
  const std::string where = path + ": " + name;
  h5::require_link(file, name, where, "episode group");
  h5::Handle group(H5Gopen2(file, name.c_str(), H5P_DEFAULT), H5Gclose);
  if (!group.valid()) throw DataError(h5::with_cause(where + ": cannot open episode group"));
  const hid_t g = group.get();
  const auto reward_dims = h5::dataset_dims(g, "rewards", where);
  if (reward_dims.size() != 1)
    throw DataError(where + "/rewards: shape " + h5::shape_text(reward_dims) + ", expected [T]");
  // Bounds T before T + 1 and T * width are formed from it.
  const hsize_t T = reward_dims[0];
  h5::checked_elements({T}, sizeof(double), where + "/rewards");
  Episode e;
  h5::read_dataset(g, "rewards", H5T_FLOAT, H5T_NATIVE_DOUBLE, {T}, e.rewards, where);
  h5::read_dataset(g, "observations", H5T_FLOAT, H5T_NATIVE_FLOAT, {T + 1, hsize_t(h.obs_dim())}, e.observations, where);
  h5::read_dataset(g, "actions", H5T_FLOAT, H5T_NATIVE_FLOAT, {T, hsize_t(h.act_dim())}, e.actions, where);
  h5::read_dataset(g, "terminations", H5T_ENUM, H5T_NATIVE_UINT8, {T}, e.terminations, where);
  h5::read_dataset(g, "truncations", H5T_ENUM, H5T_NATIVE_UINT8, {T}, e.truncations, where);
  const size_t nf = h.feature_names.size();
  e.features.resize((T + 1) * nf);
  if (nf > 0) {
    h5::require_link(g, "features", where + "/features", "group");
    h5::Handle fg(H5Gopen2(g, "features", H5P_DEFAULT), H5Gclose);
    if (!fg.valid()) throw DataError(h5::with_cause(where + "/features: cannot open group"));
    std::vector<double> column;
    for (size_t f = 0; f < nf; ++f) {
      h5::read_dataset(fg.get(), h.feature_names[f], H5T_FLOAT, H5T_NATIVE_DOUBLE, {T + 1}, column, where + "/features");
      for (size_t t = 0; t <= T; ++t) e.features[t * nf + f] = column[t];
    }
  }
  e.expert_id = h5::read_string_attr(g, "expert_id", where);
  e.context = h5::read_double_attr(g, "context", where);
  const auto seed = h5::read_double_attr(g, "seed", where);
  if (seed.size() != 1) throw DataError(where + ": attribute 'seed' must be a scalar");
  // Read the seed exactly: doubles cannot hold every 64-bit value.
  h5::Handle seed_attr(H5Aopen(g, "seed", H5P_DEFAULT), H5Aclose);
  if (H5Aread(seed_attr.get(), H5T_NATIVE_UINT64, &e.seed) < 0) throw DataError(where + ": cannot read seed");
  for (const auto& attr : h5::attr_names(g)) {
    bool standard = false;
    for (const char* known : kEpisodeAttrs) standard = standard || attr == known;
    if (!standard) {
      const auto v = h5::read_double_attr(g, attr, where);
      if (v.size() == 1) e.attributes[attr] = v[0];
    }
  }
  validate_episode(e, h, where);
  return e;
}

// The stored MJCF text, checked against its SHA-256; "" when the file has none.
std::string read_body(hid_t root, const std::string& path) {
  const std::string where = path + ": /";
  if (!h5::has_link(root, kBody, where)) return "";
  const auto dims = h5::dataset_dims(root, kBody, where);
  if (dims.size() != 1) throw DataError(where + kBody + ": shape " + h5::shape_text(dims) + ", expected [n]");
  std::vector<std::uint8_t> bytes;
  h5::read_dataset(root, kBody, H5T_INTEGER, H5T_NATIVE_UINT8, dims, bytes, where);
  std::string text(bytes.begin(), bytes.end());
  const std::string stated = h5::read_string_attr(root, "body_sha256", where), found = sha256_hex(text);
  if (stated != found)
    throw DataError(path + ": body_mjcf fails its SHA-256 (attribute body_sha256 " + stated + ", contents " + found + ")");
  return text;
}

}  // namespace

DemoSet read_demos(const std::string& path) {
  h5::silence_errors();
  if (std::FILE* f = std::fopen(path.c_str(), "rb")) {
    std::fclose(f);
  } else {
    throw DataError(path + ": no such file or not readable");
  }
  if (H5Fis_hdf5(path.c_str()) <= 0) throw DataError(path + ": not an HDF5 file");
  h5::Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!file.valid()) throw DataError(h5::with_cause(path + ": cannot open HDF5 file"));
  const hid_t root = file.get();
  const std::string where = path + ": /";
  if (h5::read_string_attr(root, "format", where) != kFormat)
    throw DataError(path + ": not a vaegail demonstration file (attribute 'format')");
  const auto version = h5::read_double_attr(root, "format_version", where);
  if (version.size() != 1 || version[0] > kDemoFormatVersion)
    throw DataError(path + ": format_version " + (version.empty() ? "?" : std::to_string(int(version[0]))) +
                    " is newer than this program reads (" + std::to_string(kDemoFormatVersion) + ")");
  DemoSet set;
  set.path = path;
  DemoHeader& h = set.header;
  h.env_id = h5::read_string_attr(root, "env_id", where);
  const auto dt = h5::read_double_attr(root, "control_timestep", where);
  h.control_timestep = dt.empty() ? 0.0 : dt[0];
  h.observation_names = parse_list(h5::read_string_attr(root, "observation_names", where), where + "observation_names");
  h.action_names = parse_list(h5::read_string_attr(root, "action_names", where), where + "action_names");
  h.feature_names = parse_list(h5::read_string_attr(root, "feature_names", where), where + "feature_names");
  h.context_names = parse_list(h5::read_string_attr(root, "context_names", where), where + "context_names");
  h.body_mjcf = read_body(root, path);
  const auto total = h5::read_double_attr(root, "total_episodes", where);
  // Each episode is a group under the root, so the count cannot exceed the root's links.
  if (total.size() != 1 || !(total[0] >= 0) || total[0] > double(h5::link_count(root)) ||
      total[0] != std::floor(total[0]))
    throw DataError(path + ": bad attribute total_episodes");
  const int episodes = static_cast<int>(total[0]);
  for (int i = 0; i < episodes; ++i) set.episodes.push_back(read_episode(root, i, h, path));
  return set;
}

}  // namespace vaegail
