#include "data/demos.h"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <thread>

#include "util/atomic_file.h"

namespace vaegail {
namespace {

DemoHeader header() {
  DemoHeader h;
  h.env_id = "toy";
  h.control_timestep = 0.025;
  h.observation_names = {"x", "v"};
  h.action_names = {"f"};
  h.feature_names = {"speed"};
  h.context_names = {"target_speed"};
  return h;
}

Episode episode(int T, float offset) {
  Episode e;
  for (int t = 0; t <= T; ++t) {
    e.observations.push_back(offset + t);
    e.observations.push_back(-offset * t);
    e.features.push_back(0.1 * t + offset);
  }
  for (int t = 0; t < T; ++t) {
    e.actions.push_back(0.5f * t);
    e.rewards.push_back(1.0 / (t + 1));
    e.terminations.push_back(t == T - 1 && offset > 1);
    e.truncations.push_back(t == T - 1 && offset <= 1);
  }
  e.expert_id = "expert_" + std::to_string(static_cast<int>(offset));
  e.context = {offset};
  e.seed = 0xFFFFFFFFFFFFFFF1ULL;  // beyond double precision: must survive exactly
  e.attributes["achieved_speed"] = offset * 0.5;
  return e;
}

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("vaegail_demos_" + name + ".h5")).string();
}

std::string write_sample(const std::string& name) {
  const std::string path = temp_path(name);
  DemoWriter w(path, header());
  w.append(episode(5, 1));
  w.append(episode(3, 2));
  w.commit();
  return path;
}

// Replaces episode_1/<field> with a dataset of the given type, shape and values.
void replace_dataset(const std::string& path, const std::string& field, hid_t type,
                     std::vector<hsize_t> dims, const void* data) {
  hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  const std::string full = "episode_1/" + field;
  H5Ldelete(f, full.c_str(), H5P_DEFAULT);
  if (data) {
    hid_t space = H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr);
    hid_t ds = H5Dcreate2(f, full.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Dwrite(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data);
    H5Dclose(ds);
    H5Sclose(space);
  }
  H5Fclose(f);
}

void expect_error(const std::string& path, const std::vector<std::string>& fragments) {
  try {
    read_demos(path);
    FAIL() << "no error for " << path;
  } catch (const DataError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    for (const auto& f : fragments) EXPECT_NE(msg.find(f), std::string::npos) << msg << " lacks " << f;
  }
}

TEST(Demos, RoundTripKeepsEverything) {
  const std::string path = write_sample("roundtrip");
  const DemoSet set = read_demos(path);
  EXPECT_EQ(set.header.env_id, "toy");
  EXPECT_EQ(set.header.observation_names, header().observation_names);
  EXPECT_EQ(set.header.context_names, header().context_names);
  EXPECT_DOUBLE_EQ(set.header.control_timestep, 0.025);
  ASSERT_EQ(set.episodes.size(), 2u);
  for (int i = 0; i < 2; ++i) {
    const Episode expected = episode(i == 0 ? 5 : 3, i + 1.f);
    const Episode& got = set.episodes[i];
    EXPECT_EQ(got.observations, expected.observations);
    EXPECT_EQ(got.actions, expected.actions);
    EXPECT_EQ(got.rewards, expected.rewards);
    EXPECT_EQ(got.terminations, expected.terminations);
    EXPECT_EQ(got.truncations, expected.truncations);
    EXPECT_EQ(got.features, expected.features);
    EXPECT_EQ(got.expert_id, expected.expert_id);
    EXPECT_EQ(got.context, expected.context);
    EXPECT_EQ(got.seed, expected.seed);
    EXPECT_EQ(got.attributes, expected.attributes);
  }
  std::remove(path.c_str());
}

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(Demos, TheSameEpisodesWrittenSecondsApartGiveTheSameBytes) {
  const std::string first = file_bytes(write_sample("bytes_a"));
  std::this_thread::sleep_for(std::chrono::milliseconds(1100));  // HDF5 times tick in seconds
  const std::string second = file_bytes(write_sample("bytes_a"));
  ASSERT_FALSE(first.empty());
  EXPECT_TRUE(first == second) << "files differ: object timestamps?";
  std::remove(temp_path("bytes_a").c_str());
}

TEST(Demos, UncommittedWriterLeavesNothingBehind) {
  const std::string path = temp_path("uncommitted");
  std::remove(path.c_str());
  {
    DemoWriter w(path, header());
    w.append(episode(4, 1));
  }
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_FALSE(std::filesystem::exists(temporary_path_for(path)));
}

TEST(Demos, WriterRejectsMalformedEpisodes) {
  DemoWriter w(temp_path("reject"), header());
  Episode bad = episode(4, 1);
  bad.actions.pop_back();
  EXPECT_THROW(w.append(bad), DataError);
  bad = episode(4, 1);
  bad.observations[3] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(w.append(bad), DataError);
}

TEST(Demos, MissingFileAndNonHdf5FileAreRejected) {
  expect_error("/nonexistent/demos.h5", {"/nonexistent/demos.h5", "no such file"});
  const std::string path = temp_path("text");
  std::ofstream(path) << "not hdf5 at all";
  expect_error(path, {path, "not an HDF5 file"});
  std::remove(path.c_str());
}

TEST(Demos, MissingDatasetIsNamed) {
  const std::string path = write_sample("missing");
  replace_dataset(path, "actions", 0, {}, nullptr);
  expect_error(path, {path, "episode_1/actions", "missing dataset"});
  std::remove(path.c_str());
}

TEST(Demos, WrongShapeIsNamed) {
  const std::string path = write_sample("shape");
  std::vector<float> values(3 * 2, 0.f);  // 3 actions of width 2 instead of width 1
  replace_dataset(path, "actions", H5T_NATIVE_FLOAT, {3, 2}, values.data());
  expect_error(path, {"episode_1/actions", "shape [3, 2], expected [3, 1]"});
  std::remove(path.c_str());
}

TEST(Demos, LengthMismatchIsNamed) {
  const std::string path = write_sample("length");
  std::vector<float> values(3 * 2, 0.f);  // T rows of observations instead of T+1
  replace_dataset(path, "observations", H5T_NATIVE_FLOAT, {3, 2}, values.data());
  expect_error(path, {"episode_1/observations", "shape [3, 2], expected [4, 2]"});
  std::remove(path.c_str());
}

TEST(Demos, WrongDtypeIsNamed) {
  const std::string path = write_sample("dtype");
  std::vector<int> values(3, 1);
  replace_dataset(path, "rewards", H5T_NATIVE_INT, {3}, values.data());
  expect_error(path, {"episode_1/rewards", "wrong dtype"});
  std::remove(path.c_str());
}

TEST(Demos, NonFiniteValuesAreNamed) {
  const std::string path = write_sample("nan");
  std::vector<float> values(3, 0.f);
  values[2] = std::numeric_limits<float>::infinity();
  replace_dataset(path, "actions", H5T_NATIVE_FLOAT, {3, 1}, values.data());
  expect_error(path, {"episode_1/actions", "non-finite", "row 2"});
  std::remove(path.c_str());
}

TEST(Demos, TruncatedFileIsRejected) {
  const std::string path = write_sample("cut");
  const auto size = std::filesystem::file_size(path);
  std::filesystem::resize_file(path, size / 2);
  try {
    read_demos(path);
    FAIL();
  } catch (const DataError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos);
  }
  std::remove(path.c_str());
}

}  // namespace
}  // namespace vaegail
