#include "util/checkpoint_file.h"

#include <gtest/gtest.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "util/atomic_file.h"
#include "util/test_child.h"
#include "util/test_error.h"
#include "util/test_small_fs.h"

namespace vaegail {
namespace {

namespace fs = std::filesystem;

// A folder of its own per test, holding latest.pt and previous.pt.
std::string checkpoint_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("vaegail_checkpoint_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

SaveToStream saving(const std::string& contents) {
  return [contents](std::ostream& out) { out << contents; };
}

// Loads files that hold "checkpoint N"; anything else fails as LibTorch does, with a trace.
struct FakeLoader {
  std::string loaded;
  LoadFromFile load() {
    return [this](const std::string& path) {
      const std::string contents = read_file(path);
      if (contents.rfind("checkpoint ", 0) != 0)
        throw std::runtime_error("PytorchStreamReader failed reading zip archive\nframe #0: c10::Error");
      loaded = contents;
    };
  }
};

TEST(CheckpointFile, ThePreviousCheckpointLiesBesideTheLatest) {
  EXPECT_EQ(previous_checkpoint_for("run/checkpoints/latest.pt"), "run/checkpoints/previous.pt");
}

TEST(CheckpointFile, ARunDirectoryMeansItsLatestCheckpointElseItsWeightsFile) {
  const std::string run = checkpoint_dir("model_file");
  EXPECT_EQ(error_of([&] { model_file(run); }),
            run + ": a directory with neither checkpoints/latest.pt nor weights.pt (not a run directory?)");
  write_file_atomically(run + "/weights.pt", "weights");
  EXPECT_EQ(model_file(run), run + "/weights.pt");
  fs::create_directories(run + "/checkpoints");
  write_file_atomically(run + "/checkpoints/latest.pt", "checkpoint 1");
  EXPECT_EQ(model_file(run), run + "/checkpoints/latest.pt");
  EXPECT_EQ(model_file(run + "/weights.pt"), run + "/weights.pt");  // a file is taken as it is
  EXPECT_EQ(model_file(run + "/missing.pt"), run + "/missing.pt");  // read_checkpoint names it
}

TEST(CheckpointFile, RotationKeepsTheCheckpointBefore) {
  const std::string latest = checkpoint_dir("rotation") + "/latest.pt";
  rotate_and_write(latest, saving("checkpoint 1"));
  rotate_and_write(latest, saving("checkpoint 2"));
  EXPECT_EQ(read_file(latest), "checkpoint 2");
  EXPECT_EQ(read_file(previous_checkpoint_for(latest)), "checkpoint 1");
}

TEST(CheckpointFile, AFailingDiskLeavesBothCheckpointsAndNoTemporaryFile) {
  const std::string latest = checkpoint_dir("failing") + "/latest.pt";
  rotate_and_write(latest, saving("checkpoint 1"));
  rotate_and_write(latest, saving("checkpoint 2"));
  const ChildOutcome outcome = run_in_child(
      [&](std::string& report) {
        limit_file_size(4096);
        report = error_of([&] { rotate_and_write(latest, saving("checkpoint " + std::string(8192, '3'))); });
        return 0;
      },
      10);
  ASSERT_EQ(outcome.end, ChildOutcome::End::kExited);
  EXPECT_EQ(outcome.report, latest + ": write failed: " + std::strerror(EFBIG));
  EXPECT_FALSE(leaves_temporary(latest));
  FakeLoader loader;
  EXPECT_EQ(resume_checkpoint(latest, loader.load()).path, latest);
  EXPECT_EQ(loader.loaded, "checkpoint 2");
  EXPECT_EQ(read_file(previous_checkpoint_for(latest)), "checkpoint 1");
}

// The same on a real full file system (ENOSPC wherever the tmpfs runs out); once there is room
// again the rotation goes on from the checkpoint before the failure.
TEST(CheckpointFile, AFullFileSystemLeavesTheCheckpointAndNoTemporaryFileUntilThereIsRoom) {
  SmallFileSystem small(256 * 1024);
  if (!small.mounted()) GTEST_SKIP() << small.why_not();
  const std::string latest = small.path("latest.pt");
  int saves = 0;
  expect_refused_on_a_full_disk_then_saved(
      small, latest, [&] { rotate_and_write(latest, saving("checkpoint " + std::to_string(++saves))); });
  EXPECT_EQ(read_file(latest), "checkpoint 3");
  EXPECT_EQ(read_file(previous_checkpoint_for(latest)), "checkpoint 1");
}

TEST(CheckpointFile, AnUnreadableCheckpointIsOneLineNamingIt) {
  const std::string latest = checkpoint_dir("unreadable") + "/latest.pt";
  write_file_atomically(latest, "not a checkpoint");
  FakeLoader loader;
  EXPECT_EQ(error_of([&] { read_checkpoint(latest, loader.load()); }),
            latest + ": unreadable checkpoint (PytorchStreamReader failed reading zip archive)");
  write_file_atomically(latest, "PK\x03\x04 a zip archive cut short");
  EXPECT_EQ(error_of([&] { read_checkpoint(latest, loader.load()); }),
            latest + ": damaged checkpoint (truncated: no zip directory at the end)");
  const std::string missing = latest + ".missing";
  EXPECT_EQ(error_of([&] { read_checkpoint(missing, loader.load()); }), missing + ": no such checkpoint");
}

TEST(CheckpointFile, ACheckpointOfAnotherRunIsNotPassedOver) {
  const std::string latest = checkpoint_dir("other_run") + "/latest.pt";
  rotate_and_write(latest, saving("checkpoint 1"));
  rotate_and_write(latest, saving("checkpoint 2"));
  const LoadFromFile wrong_config = [](const std::string& path) {
    throw std::invalid_argument(path + ": checkpoint was trained with a different VaeConfig");
  };
  EXPECT_THROW(resume_checkpoint(latest, wrong_config), std::invalid_argument);
  EXPECT_TRUE(fs::exists(latest));
}

TEST(CheckpointFile, ResumingFallsBackToThePreviousAndSetsTheDamagedOneAside) {
  const std::string latest = checkpoint_dir("fallback") + "/latest.pt";
  const std::string previous = previous_checkpoint_for(latest);
  rotate_and_write(latest, saving("checkpoint 1"));
  rotate_and_write(latest, saving("truncated"));
  FakeLoader loader;
  const ResumedCheckpoint resumed = resume_checkpoint(latest, loader.load());
  EXPECT_EQ(resumed.path, previous);
  EXPECT_EQ(loader.loaded, "checkpoint 1");
  EXPECT_EQ(resumed.message(), "resumed from " + previous + " (" + latest +
                                   ": unreadable checkpoint (PytorchStreamReader failed reading zip archive); kept as " +
                                   latest + ".corrupt)");
  EXPECT_TRUE(fs::exists(latest + ".corrupt"));
  // The next checkpoint keeps the good one as previous, not the damaged one.
  rotate_and_write(latest, saving("checkpoint 2"));
  EXPECT_EQ(read_file(previous), "checkpoint 1");
}

TEST(CheckpointFile, ResumingBetweenTheTwoRenamesOfARotationTakesThePrevious) {
  const std::string latest = checkpoint_dir("between") + "/latest.pt";
  write_file_atomically(previous_checkpoint_for(latest), "checkpoint 1");
  FakeLoader loader;
  const ResumedCheckpoint resumed = resume_checkpoint(latest, loader.load());
  EXPECT_EQ(resumed.path, previous_checkpoint_for(latest));
  EXPECT_EQ(resumed.skipped, latest + ": missing");
}

TEST(CheckpointFile, ResumingAFreshRunLoadsNothing) {
  FakeLoader loader;
  const ResumedCheckpoint resumed = resume_checkpoint(checkpoint_dir("fresh") + "/latest.pt", loader.load());
  EXPECT_EQ(resumed.path, "");
  EXPECT_EQ(resumed.message(), "");
  EXPECT_EQ(loader.loaded, "");
}

TEST(CheckpointFile, WhenNeitherLoadsTheErrorIsOneLineNamingBoth) {
  const std::string latest = checkpoint_dir("neither") + "/latest.pt";
  rotate_and_write(latest, saving("garbage"));
  rotate_and_write(latest, saving("garbage too"));
  FakeLoader loader;
  const std::string error = error_of([&] { resume_checkpoint(latest, loader.load()); });
  EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  EXPECT_EQ(error.rfind(latest + ": unreadable checkpoint", 0), 0u) << error;
  EXPECT_NE(error.find(previous_checkpoint_for(latest) + ": unreadable checkpoint"), std::string::npos) << error;
  EXPECT_TRUE(fs::exists(latest));  // nothing set aside when there is nothing better
}

}  // namespace
}  // namespace vaegail
