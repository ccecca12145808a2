#include "data/foreign_demos.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>

#include "data/demos_test_support.h"
#include "data/npy.h"
#include "env/generic_task.h"
#include "util/atomic_file.h"

namespace vaegail {
namespace {

namespace fs = std::filesystem;

const std::string kPython = "/usr/bin/python3";  // Debian's, with python3-h5py and python3-numpy

bool have_fixture_tools() { return std::system((kPython + " -c 'import h5py, numpy' 2> /dev/null").c_str()) == 0; }

// Runs src/data/testdata/write_foreign_demos.py MODE PATH; returns PATH.
std::string fixture(const std::string& mode, const std::string& name) {
  const std::string path = (fs::temp_directory_path() / ("vaegail_foreign_" + name)).string();
  fs::remove_all(path);
  const std::string script = std::string(VAEGAIL_SOURCE_DIR) + "/src/data/testdata/write_foreign_demos.py";
  EXPECT_EQ(std::system((kPython + " " + script + " " + mode + " " + path).c_str()), 0) << mode;
  return path;
}

void expect_data_error(const std::function<void()>& f, const std::string& fragment) {
  try {
    f();
    FAIL() << "no error; expected " << fragment;
  } catch (const DataError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
  }
}

// Sets an environment variable for the life of the object, then puts back what was there.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::string& value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    setenv(name, value.c_str(), 1);
  }
  ~ScopedEnv() { old_ ? setenv(name_, old_->c_str(), 1) : unsetenv(name_); }

 private:
  const char* name_;
  std::optional<std::string> old_;
};

void expect_tiny_minari_dataset(const DemoSet& set) {
  EXPECT_EQ(set.header.env_id, "TinyHopper-v0");  // env_spec's id
  EXPECT_EQ(set.header.observation_names, (std::vector<std::string>{"obs_0", "obs_1", "obs_2"}));
  EXPECT_EQ(set.header.action_names, (std::vector<std::string>{"act_0", "act_1"}));
  ASSERT_EQ(set.episodes.size(), 2u);
  for (int ep = 0; ep < 2; ++ep) {
    const Episode& e = set.episodes[ep];
    const int T = ep == 0 ? 4 : 2;
    ASSERT_EQ(e.length(), T);
    EXPECT_EQ(e.seed, 42u + ep);
    for (int t = 0; t <= T; ++t)
      for (int k = 0; k < 3; ++k) EXPECT_FLOAT_EQ(e.observations[t * 3 + k], ep * 10 + t + 0.1 * k);
    for (int t = 0; t < T; ++t) {
      for (int k = 0; k < 2; ++k) EXPECT_FLOAT_EQ(e.actions[t * 2 + k], 0.5 * t - k + ep);
      EXPECT_DOUBLE_EQ(e.rewards[t], t * 0.25 + ep);
      EXPECT_EQ(e.terminations[t], ep == 0 && t == T - 1);
      EXPECT_EQ(e.truncations[t], ep == 1 && t == T - 1);
    }
  }
}

// Minari keeps dataset ID in ROOT/ID/data/; import takes the dataset directory, its data folder or
// the ID, the same dataset each way.
TEST(ForeignDemos, AMinariDatasetWrittenByH5pyImportsByDirectoryDataFolderOrId) {
  if (!have_fixture_tools()) GTEST_SKIP() << "no python3-h5py";
  const std::string root = (fs::temp_directory_path() / "vaegail_foreign_minari_root").string();
  fs::remove_all(root);
  const std::string dataset = fixture("minari", "minari_root/tiny/expert-v0");
  SCOPED_TRACE(dataset);
  {
    SCOPED_TRACE("directory");
    expect_tiny_minari_dataset(import_minari(dataset));
  }
  {
    SCOPED_TRACE("data folder");
    expect_tiny_minari_dataset(import_minari(dataset + "/data"));
  }
  {
    SCOPED_TRACE("ID");
    const ScopedEnv datasets_path("MINARI_DATASETS_PATH", root);
    EXPECT_EQ(minari_datasets_root(), root);
    EXPECT_EQ(minari_data_dir("tiny/expert-v0"), root + "/tiny/expert-v0/data");
    expect_tiny_minari_dataset(import_minari("tiny/expert-v0"));
    expect_data_error([&] { import_minari("tiny/expert-v9"); },
                      "tiny/expert-v9: no Minari dataset (no tiny/expert-v9/data/metadata.json, "
                      "tiny/expert-v9/metadata.json, " + root + "/tiny/expert-v9/data/metadata.json)");
  }
  {
    const ScopedEnv home("HOME", "/home/someone"), unset("MINARI_DATASETS_PATH", "");
    EXPECT_EQ(minari_datasets_root(), "/home/someone/.minari/datasets");  // Minari's default
  }
  fs::remove_all(root);
}

TEST(ForeignDemos, AMinariDictSpaceIsRefusedByName) {
  if (!have_fixture_tools()) GTEST_SKIP() << "no python3-h5py";
  const std::string dir = fixture("minari_dict", "minari_dict");
  expect_data_error([&] { import_minari(dir); }, "observation_space is a Dict space: only Box");
  expect_data_error([&] { import_minari(dir + "/nothing"); }, "nothing: no Minari dataset (no " + dir + "/nothing/data/metadata.json");
}

TEST(ForeignDemos, AnImitationNpzImportsSplitByItsIndices) {
  if (!have_fixture_tools()) GTEST_SKIP() << "no python3-numpy";
  const DemoSet set = import_imitation_npz(fixture("npz", "trajectories.npz"));
  const int lengths[] = {4, 2, 3};
  const bool terminal[] = {true, false, true};
  ASSERT_EQ(set.episodes.size(), 3u);
  EXPECT_EQ(set.header.obs_dim(), 2);
  EXPECT_EQ(set.header.act_dim(), 1);
  for (int i = 0; i < 3; ++i) {
    const Episode& e = set.episodes[i];
    ASSERT_EQ(e.length(), lengths[i]);
    for (int t = 0; t <= lengths[i]; ++t) {
      EXPECT_FLOAT_EQ(e.observations[2 * t], i * 100 + t);
      EXPECT_FLOAT_EQ(e.observations[2 * t + 1], i * 100 - t);
    }
    for (int t = 0; t < lengths[i]; ++t) {
      EXPECT_FLOAT_EQ(e.actions[t], i + 0.5 * t);
      EXPECT_DOUBLE_EQ(e.rewards[t], i);
    }
    EXPECT_EQ(e.terminations.back(), terminal[i]);
    EXPECT_EQ(e.truncations.back(), !terminal[i]);
  }
}

TEST(ForeignDemos, ADamagedNpzIsRejectedNamingTheFile) {
  if (!have_fixture_tools()) GTEST_SKIP() << "no python3-numpy";
  const std::string path = fixture("npz", "damaged.npz");
  std::string bytes = read_file(path);
  bytes[bytes.size() / 3] ^= 0x5A;
  std::ofstream(path, std::ios::binary) << bytes;
  expect_data_error([&] { import_imitation_npz(path); }, path);
  const std::string header = "{'descr': '|O', 'fortran_order': False, 'shape': (2,), }";
  const std::string object_array = std::string("\x93NUMPY\x01\x00", 8) + char(header.size()) + '\0' + header;
  expect_data_error([&] { parse_npy(object_array, "x"); }, "x: an object array");
}

TEST(ForeignDemos, AnExportedDirectoryReadsBackAndHasMinarisLayout) {
  const std::string toy = write_toy_file("export_source");
  DemoSet set = read_demos(toy);
  set.header.body_mjcf = "<mujoco/>";
  const std::string dir = (fs::temp_directory_path() / "vaegail_foreign_export").string();
  fs::remove_all(dir);
  export_minari(set, dir, "vaegail/toy-v0");
  EXPECT_TRUE(fs::is_regular_file(dir + "/data/main_data.hdf5"));  // Minari's layout: DIR/data/
  EXPECT_TRUE(fs::is_regular_file(dir + "/data/metadata.json"));
  const DemoSet back = import_minari(dir);
  EXPECT_EQ(toy_contents_difference(back), "");
  EXPECT_EQ(back.header.body_mjcf, "<mujoco/>");
  EXPECT_THROW(export_minari(set, dir, "vaegail/toy-v0"), std::runtime_error);  // exists
  export_minari(set, dir, "vaegail/toy-v0", /*replace=*/true);
  for (const auto& entry : fs::directory_iterator(fs::temp_directory_path()))
    EXPECT_EQ(entry.path().string().find("vaegail_foreign_export."), std::string::npos) << entry.path();
  if (!have_fixture_tools()) GTEST_SKIP() << "no python3-h5py to read it as Minari does";
  const std::string script = std::string(VAEGAIL_SOURCE_DIR) + "/src/data/testdata/write_foreign_demos.py";
  EXPECT_EQ(std::system((kPython + " " + script + " check_minari " + dir).c_str()), 0);
  fs::remove_all(dir);
  std::remove(toy.c_str());
}

TEST(ForeignDemos, AdoptingAnEnvironmentNamesTheComponentsAndChecksDimensions) {
  const std::string xml = R"(<mujoco><worldbody><body><joint name="hinge" type="hinge"/>
    <geom size="0.1"/></body></worldbody><actuator><motor name="push" joint="hinge"/></actuator></mujoco>)";
  const GenericTaskEnv env(MujocoModel::from_xml("pendulum.xml", xml), {});
  const std::string toy = write_toy_file("adopt");
  DemoSet set = read_demos(toy);  // 2 observations, 1 action: the pendulum's
  adopt_env(set, env);
  EXPECT_EQ(set.header.env_id, "pendulum.xml");
  EXPECT_EQ(set.header.observation_names, (std::vector<std::string>{"qpos:hinge", "qvel:hinge"}));
  EXPECT_EQ(set.header.body_mjcf, xml);
  EXPECT_TRUE(set.header.context_names.empty());
  EXPECT_TRUE(set.episodes[0].context.empty());
  set.header.observation_names.push_back("extra");
  expect_data_error([&] { adopt_env(set, env); }, "3/1 components, task 'pendulum.xml' has 2/1");
  std::remove(toy.c_str());
}

}  // namespace
}  // namespace vaegail
