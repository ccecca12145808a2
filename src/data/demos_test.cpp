#include "data/demos.h"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <thread>

#include "data/demos_test_support.h"
#include "data/hdf5_handle.h"
#include "util/atomic_file.h"
#include "util/test_small_fs.h"

namespace vaegail {
namespace {

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
  const std::string path = write_toy_file("roundtrip");
  EXPECT_EQ(toy_contents_difference(read_demos(path)), "");
  std::remove(path.c_str());
}

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(Demos, TheSameEpisodesWrittenSecondsApartGiveTheSameBytes) {
  const std::string first = file_bytes(write_toy_file("bytes_a"));
  std::this_thread::sleep_for(std::chrono::milliseconds(1100));  // HDF5 times tick in seconds
  const std::string second = file_bytes(write_toy_file("bytes_a"));
  ASSERT_FALSE(first.empty());
  EXPECT_TRUE(first == second) << "files differ: object timestamps?";
  std::remove(temp_demo_path("bytes_a").c_str());
}

TEST(Demos, UncommittedWriterLeavesNothingBehind) {
  const std::string path = temp_demo_path("uncommitted");
  std::remove(path.c_str());
  {
    DemoWriter w(path, toy_header());
    w.append(toy_episode(4, 1));
  }
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_FALSE(std::filesystem::exists(temporary_path_for(path)));
}

// On a full file system HDF5's failure is one line naming the file and the cause; neither a
// temporary nor a half file is left, and the file before stays as it was.
TEST(Demos, AFileOnAFullDiskIsRefusedInOneLineAndTheOneBeforeKept) {
  SmallFileSystem small(512 * 1024);
  if (!small.mounted()) GTEST_SKIP() << small.why_not();
  const std::string path = small.path("demos.h5");
  expect_refused_on_a_full_disk_then_saved(small, path, [&] { write_toy_file_at(path); });
  EXPECT_EQ(toy_contents_difference(read_demos(path)), "");
}

TEST(Demos, WriterRejectsMalformedEpisodes) {
  DemoWriter w(temp_demo_path("reject"), toy_header());
  Episode bad = toy_episode(4, 1);
  bad.actions.pop_back();
  EXPECT_THROW(w.append(bad), DataError);
  bad = toy_episode(4, 1);
  bad.observations[3] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(w.append(bad), DataError);
}

TEST(Demos, MissingFileAndNonHdf5FileAreRejected) {
  expect_error("/nonexistent/demos.h5", {"/nonexistent/demos.h5", "no such file"});
  const std::string path = temp_demo_path("text");
  std::ofstream(path) << "not hdf5 at all";
  expect_error(path, {path, "not an HDF5 file"});
  std::remove(path.c_str());
}

TEST(Demos, MissingDatasetIsNamed) {
  const std::string path = write_toy_file("missing");
  replace_dataset(path, "actions", 0, {}, nullptr);
  expect_error(path, {path, "episode_1/actions", "missing dataset"});
  std::remove(path.c_str());
}

TEST(Demos, WrongShapeIsNamed) {
  const std::string path = write_toy_file("shape");
  std::vector<float> values(3 * 2, 0.f);  // 3 actions of width 2 instead of width 1
  replace_dataset(path, "actions", H5T_NATIVE_FLOAT, {3, 2}, values.data());
  expect_error(path, {"episode_1/actions", "shape [3, 2], expected [3, 1]"});
  std::remove(path.c_str());
}

TEST(Demos, LengthMismatchIsNamed) {
  const std::string path = write_toy_file("length");
  std::vector<float> values(3 * 2, 0.f);  // T rows of observations instead of T+1
  replace_dataset(path, "observations", H5T_NATIVE_FLOAT, {3, 2}, values.data());
  expect_error(path, {"episode_1/observations", "shape [3, 2], expected [4, 2]"});
  std::remove(path.c_str());
}

TEST(Demos, WrongDtypeIsNamed) {
  const std::string path = write_toy_file("dtype");
  std::vector<int> values(3, 1);
  replace_dataset(path, "rewards", H5T_NATIVE_INT, {3}, values.data());
  expect_error(path, {"episode_1/rewards", "wrong dtype"});
  std::remove(path.c_str());
}

TEST(Demos, NonFiniteValuesAreNamed) {
  const std::string path = write_toy_file("nan");
  std::vector<float> values(3, 0.f);
  values[2] = std::numeric_limits<float>::infinity();
  replace_dataset(path, "actions", H5T_NATIVE_FLOAT, {3, 1}, values.data());
  expect_error(path, {"episode_1/actions", "non-finite", "row 2"});
  std::remove(path.c_str());
}

TEST(Demos, TruncatedFileIsRejected) {
  const std::string path = write_toy_file("cut");
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

// ---- files that check themselves --------------------------------------------------------

std::vector<std::string> object_paths(hid_t file, H5O_type_t type) {
  struct Visit {
    H5O_type_t type;
    std::vector<std::string> paths;
  } visit{type, {}};
  H5Ovisit2(file, H5_INDEX_NAME, H5_ITER_INC,
            [](hid_t, const char* name, const H5O_info_t* info, void* data) -> herr_t {
              auto* v = static_cast<Visit*>(data);
              if (info->type == v->type) v->paths.emplace_back(name);
              return 0;
            },
            &visit, H5O_INFO_BASIC);
  return visit.paths;
}

bool has_variable_length_string_attr(hid_t object) {
  bool found = false;
  hsize_t position = 0;
  H5Aiterate2(object, H5_INDEX_NAME, H5_ITER_INC, &position,
              [](hid_t obj, const char* name, const H5A_info_t*, void* out) -> herr_t {
                const hid_t attr = H5Aopen(obj, name, H5P_DEFAULT), type = H5Aget_type(attr);
                if (H5Tis_variable_str(type) > 0) *static_cast<bool*>(out) = true;
                H5Tclose(type);
                H5Aclose(attr);
                return 0;
              },
              &found);
  return found;
}

TEST(Demos, WrittenFilesChecksumTheirMetadataAndEveryValue) {
  const std::string path = write_toy_file("checksums");
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  H5F_info2_t info;
  ASSERT_GE(H5Fget_info2(f, &info), 0);
  EXPECT_GE(info.super.version, 3u) << "superblock without checksum: not the 1.10 format";
  const auto datasets = object_paths(f, H5O_TYPE_DATASET);
  EXPECT_EQ(datasets.size(), 2u * 6);  // 5 arrays and 1 feature per episode
  for (const auto& name : datasets) {
    const hid_t ds = H5Dopen2(f, name.c_str(), H5P_DEFAULT), plist = H5Dget_create_plist(ds);
    EXPECT_EQ(H5Pget_layout(plist), H5D_CHUNKED) << name;
    unsigned flags = 0;
    size_t n = 0;
    unsigned filter_info = 0;
    EXPECT_GE(H5Pget_filter_by_id2(plist, H5Z_FILTER_FLETCHER32, &flags, &n, nullptr, 0, nullptr, &filter_info), 0)
        << name << " has no Fletcher-32 checksum";
    H5Pclose(plist);
    H5Dclose(ds);
  }
  for (const auto& group : object_paths(f, H5O_TYPE_GROUP)) {
    const hid_t g = H5Gopen2(f, group.c_str(), H5P_DEFAULT);
    EXPECT_FALSE(has_variable_length_string_attr(g)) << group << ": a string in the global heap";
    H5Gclose(g);
  }
  H5Fclose(f);
  std::remove(path.c_str());
}

// Overwrites `count` bytes at `offset` with their complement.
void flip_bytes(const std::string& path, std::uint64_t offset, int count) {
  std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
  for (int i = 0; i < count; ++i) {
    file.seekg(static_cast<std::streamoff>(offset + i));
    const char byte = static_cast<char>(~file.get());
    file.seekp(static_cast<std::streamoff>(offset + i));
    file.put(byte);
  }
}

// Where the stored (filtered) bytes of a one-chunk dataset lie in the file.
std::pair<haddr_t, hsize_t> chunk_extent(const std::string& path, const std::string& dataset) {
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t ds = H5Dopen2(f, dataset.c_str(), H5P_DEFAULT), space = H5Dget_space(ds);
  hsize_t offset[2];
  unsigned filter_mask = 0;
  haddr_t address = HADDR_UNDEF;
  hsize_t size = 0;
  H5Dget_chunk_info(ds, space, 0, offset, &filter_mask, &address, &size);
  H5Sclose(space);
  H5Dclose(ds);
  H5Fclose(f);
  return {address, size};
}

TEST(Demos, AFlippedByteAmongTheValuesIsRejectedNamingTheDataset) {
  const std::string path = write_toy_file("flip_value");
  const auto [address, size] = chunk_extent(path, "episode_1/observations");
  ASSERT_NE(address, HADDR_UNDEF);
  flip_bytes(path, address + size / 2, 1);
  expect_error(path, {path, "episode_1/observations", "Fletcher32"});
  std::remove(path.c_str());
}

TEST(Demos, AFlippedByteInTheMetadataIsRejected) {
  const std::string path = write_toy_file("flip_superblock");
  flip_bytes(path, 20, 1);  // inside the superblock, before its checksum
  expect_error(path, {path});
  std::remove(path.c_str());
}

const char* const kBodyText = "<mujoco model=\"mine\"><worldbody><body><geom size=\"0.1\"/></body></worldbody></mujoco>";

std::string write_file_with_body(const std::string& name) {
  const std::string path = temp_demo_path(name);
  DemoHeader h = toy_header();
  h.body_mjcf = kBodyText;
  DemoWriter w(path, h);
  for (int i = 0; i < 2; ++i) w.append(toy_file_episode(i));
  w.commit();
  return path;
}

TEST(Demos, TheBodyTravelsWithTheFileInAChecksummedDataset) {
  const std::string path = write_file_with_body("body");
  const DemoSet set = read_demos(path);
  EXPECT_EQ(set.header.body_mjcf, kBodyText);
  EXPECT_EQ(toy_contents_difference(set), "");
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t ds = H5Dopen2(f, "body_mjcf", H5P_DEFAULT), plist = H5Dget_create_plist(ds);
  unsigned flags = 0, filter_info = 0;
  size_t n = 0;
  EXPECT_GE(H5Pget_filter_by_id2(plist, H5Z_FILTER_FLETCHER32, &flags, &n, nullptr, 0, nullptr, &filter_info), 0);
  H5Pclose(plist);
  H5Dclose(ds);
  H5Fclose(f);
  EXPECT_EQ(read_demos(write_toy_file("no_body")).header.body_mjcf, "");  // built-in tasks store none
  std::remove(path.c_str());
}

TEST(Demos, ABodyThatDoesNotMatchItsHashIsRejected) {
  const std::string path = write_file_with_body("body_hash");
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(H5Adelete(f, "body_sha256"), 0);
  h5::write_string_attr(f, "body_sha256", std::string(64, '0'));
  H5Fclose(f);
  expect_error(path, {path, "body_mjcf fails its SHA-256"});
  const std::string flipped = write_file_with_body("body_flip");
  const auto [address, size] = chunk_extent(flipped, "body_mjcf");
  flip_bytes(flipped, address + size / 2, 1);
  expect_error(flipped, {flipped, "body_mjcf", "Fletcher32"});
  std::remove(path.c_str());
  std::remove(flipped.c_str());
}

TEST(Demos, ACorruptDimensionIsRejectedBeforeAnythingIsAllocated) {
  const std::string path = write_toy_file("huge");
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  H5Ldelete(f, "episode_1/rewards", H5P_DEFAULT);
  const hsize_t steps = hsize_t(1) << 40;  // 8 TiB of rewards, never allocated in the file
  const hid_t space = H5Screate_simple(1, &steps, nullptr);
  H5Dclose(H5Dcreate2(f, "episode_1/rewards", H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  H5Sclose(space);
  H5Fclose(f);
  expect_error(path, {path, "episode_1/rewards", "corrupt dimensions"});
  std::remove(path.c_str());
}

// ---- files of other tools ------------------------------------------------------------------

// The toy file as other writers lay it out: the earliest file format (no checksums),
// datasets contiguous, compact or gzip-chunked in turn, variable-length strings, integer
// counts, and objects the reader does not know.
class OtherLayoutWriter {
 public:
  explicit OtherLayoutWriter(const std::string& path)
      : file_(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT)) {}
  ~OtherLayoutWriter() { H5Fclose(file_); }
  hid_t file() const { return file_; }

  void dataset(hid_t parent, const char* name, hid_t type, std::vector<hsize_t> dims, const void* data) {
    const hid_t space = H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr);
    const hid_t plist = H5Pcreate(H5P_DATASET_CREATE);
    const int layout = next_layout_++ % 3;
    if (layout == 1) H5Pset_layout(plist, H5D_COMPACT);
    if (layout == 2) {
      H5Pset_chunk(plist, static_cast<int>(dims.size()), dims.data());
      H5Pset_deflate(plist, 6);
    }
    const hid_t ds = H5Dcreate2(parent, name, type, space, H5P_DEFAULT, plist, H5P_DEFAULT);
    H5Dwrite(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data);
    H5Dclose(ds);
    H5Pclose(plist);
    H5Sclose(space);
  }

  static void string_attr(hid_t object, const char* name, const std::string& value) {
    const hid_t type = H5Tcopy(H5T_C_S1), space = H5Screate(H5S_SCALAR);
    H5Tset_size(type, H5T_VARIABLE);
    H5Tset_cset(type, H5T_CSET_UTF8);
    const hid_t attr = H5Acreate2(object, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
    const char* text = value.c_str();
    H5Awrite(attr, type, &text);
    H5Aclose(attr);
    H5Sclose(space);
    H5Tclose(type);
  }

  static void attr(hid_t object, const char* name, hid_t type, const void* value, hsize_t n = 0) {
    const hid_t space = n ? H5Screate_simple(1, &n, nullptr) : H5Screate(H5S_SCALAR);
    const hid_t a = H5Acreate2(object, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(a, type, value);
    H5Aclose(a);
    H5Sclose(space);
  }

 private:
  hid_t file_;
  int next_layout_ = 0;
};

std::string write_toy_file_in_other_layout(const std::string& name) {
  const std::string path = temp_demo_path(name);
  OtherLayoutWriter w(path);
  const hid_t root = w.file();
  w.string_attr(root, "format", "vaegail-demos");
  const long long version = 1, episodes = 2, steps = 8;
  w.attr(root, "format_version", H5T_NATIVE_LLONG, &version);
  w.attr(root, "total_episodes", H5T_NATIVE_LLONG, &episodes);
  w.attr(root, "total_steps", H5T_NATIVE_LLONG, &steps);
  w.string_attr(root, "env_id", "toy");
  const double dt = 0.025;
  w.attr(root, "control_timestep", H5T_NATIVE_DOUBLE, &dt);
  w.string_attr(root, "observation_names", R"(["x", "v"])");
  w.string_attr(root, "action_names", R"(["f"])");
  w.string_attr(root, "feature_names", R"(["speed"])");
  w.string_attr(root, "context_names", R"(["target_speed"])");
  const hid_t extras = H5Gcreate2(root, "extras", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  const double note[3] = {1, 2, 3};
  w.dataset(extras, "notes", H5T_NATIVE_DOUBLE, {3}, note);
  H5Gclose(extras);
  const hid_t boolean = H5Tenum_create(H5T_NATIVE_INT8);
  const signed char no = 0, yes = 1;
  H5Tenum_insert(boolean, "FALSE", &no);
  H5Tenum_insert(boolean, "TRUE", &yes);
  for (int i = 0; i < 2; ++i) {
    const Episode e = toy_file_episode(i);
    const hsize_t T = e.rewards.size();
    const hid_t g = H5Gcreate2(root, ("episode_" + std::to_string(i)).c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    w.dataset(g, "observations", H5T_NATIVE_FLOAT, {T + 1, 2}, e.observations.data());
    w.dataset(g, "actions", H5T_NATIVE_FLOAT, {T, 1}, e.actions.data());
    w.dataset(g, "rewards", H5T_NATIVE_DOUBLE, {T}, e.rewards.data());
    w.dataset(g, "terminations", boolean, {T}, e.terminations.data());
    w.dataset(g, "truncations", boolean, {T}, e.truncations.data());
    w.dataset(g, "infos", H5T_NATIVE_DOUBLE, {T}, e.rewards.data());  // unknown to the reader
    const hid_t features = H5Gcreate2(g, "features", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    w.dataset(features, "speed", H5T_NATIVE_DOUBLE, {T + 1}, e.features.data());
    H5Gclose(features);
    const long long id = i, total = static_cast<long long>(T);
    w.attr(g, "id", H5T_NATIVE_LLONG, &id);
    w.attr(g, "total_steps", H5T_NATIVE_LLONG, &total);
    w.attr(g, "seed", H5T_NATIVE_UINT64, &e.seed);
    w.string_attr(g, "expert_id", e.expert_id);
    w.attr(g, "context", H5T_NATIVE_DOUBLE, e.context.data(), 1);
    w.attr(g, "achieved_speed", H5T_NATIVE_DOUBLE, &e.attributes.at("achieved_speed"));
    H5Gclose(g);
  }
  H5Tclose(boolean);
  return path;
}

TEST(Demos, FilesInTheLayoutsOfOtherToolsStillLoad) {
  const std::string path = write_toy_file_in_other_layout("other_layout");
  EXPECT_EQ(toy_contents_difference(read_demos(path)), "");
  std::remove(path.c_str());
}

TEST(Demos, FilesWrittenByH5pyStillLoad) {
  const std::string path = temp_demo_path("h5py");
  const std::string script = std::string(VAEGAIL_SOURCE_DIR) + "/src/data/testdata/write_h5py_demos.py";
  // The system interpreter: python3-h5py is a Debian package, not installed by setup.sh.
  if (std::system("/usr/bin/python3 -c 'import h5py' 2> /dev/null") != 0) GTEST_SKIP() << "no python3-h5py";
  ASSERT_EQ(std::system(("/usr/bin/python3 " + script + " " + path).c_str()), 0);
  EXPECT_EQ(toy_contents_difference(read_demos(path)), "");
  std::remove(path.c_str());
}

}  // namespace
}  // namespace vaegail
