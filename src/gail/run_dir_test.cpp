#include "gail/run_dir.h"

#include <gtest/gtest.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "gail/gail_agent.h"
#include "gail/test_support.h"  // one Torch thread: the tests fork
#include "util/atomic_file.h"
#include "util/checkpoint_file.h"
#include "util/test_child.h"
#include "util/test_small_fs.h"

namespace vaegail {
namespace {

namespace fs = std::filesystem;

std::string run_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("vaegail_run_dir_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir / "checkpoints");
  return dir.string();
}

std::shared_ptr<Agent> agent_with_weights(float value) {
  AgentOptions o;
  o.obs_dim = 3;
  o.act_dim = 2;
  o.policy_hidden = o.critic_hidden = {16};
  auto agent = Agent::make_gaussian(o);
  torch::NoGradGuard no_grad;
  for (auto& p : agent->parameters()) p.fill_(value);
  return agent;
}

// The layout the trainers write: the agent under "agent".
void checkpoint_agent(const std::string& dir, float value) {
  rotate_and_write(run_checkpoint(dir), [&](std::ostream& out) {
    torch::serialize::OutputArchive root, archive;
    agent_with_weights(value)->save(archive);
    root.write("agent", archive);
    root.save_to(out);
  });
}

float first_weight_of_run(const std::string& dir) {
  auto agent = agent_with_weights(0);
  load_run_agent(dir, *agent, torch::kCPU);
  return agent->parameters().front().flatten()[0].item<float>();
}

// A run started before `discriminator_minibatches` existed lacks the key and was read with 1: resuming it with 1
// agrees, with another value names the setting.
TEST(RunDir, AnOlderConfigResumesWithTheValuesItWasReadWith) {
  const std::string path = run_dir("older_config") + "/config.json";
  GailOptions options;
  auto older = nlohmann::json(options);
  older.erase("discriminator_minibatches");
  write_file_atomically(path, older.dump(2));

  options.discriminator_minibatches = 1;
  EXPECT_NO_THROW(check_or_write_config(path, options, {}));
  options.discriminator_minibatches = 10;
  try {
    check_or_write_config(path, options, {});
    FAIL() << "a changed setting was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("/discriminator_minibatches"), std::string::npos) << e.what();
  }
}

// A run's config.json on a full file system: refused in one line, the config before kept.
TEST(RunDir, AConfigOnAFullDiskIsRefusedAndTheOneBeforeKept) {
  SmallFileSystem small(256 * 1024);
  if (!small.mounted()) GTEST_SKIP() << small.why_not();
  const std::string path = small.path("config.json");
  GailOptions options;
  options.iterations = 1;
  expect_refused_on_a_full_disk_then_saved(small, path, [&] {
    ++options.iterations;  // a resumable key: each call rewrites the file
    check_or_write_config(path, options, {"iterations"});
  });
  EXPECT_EQ(nlohmann::json::parse(read_file(path)).at("iterations"), 4);
}

TEST(RunDir, ACheckpointOnAFailingDiskEndsInOneLineAndKeepsBothCheckpoints) {
  const std::string dir = run_dir("failing"), latest = run_checkpoint(dir);
  checkpoint_agent(dir, 1);
  checkpoint_agent(dir, 2);
  const auto size = fs::file_size(latest);
  // LibTorch's save_to(file) aborts the process here (exit 134); the serialised archive does not.
  const ChildOutcome outcome = run_in_child(
      [&](std::string& report) {
        limit_file_size(size / 2);
        try {
          checkpoint_agent(dir, 3);
        } catch (const std::exception& e) {
          report = e.what();
        }
        return 0;
      },
      60);
  ASSERT_EQ(outcome.end, ChildOutcome::End::kExited) << "signal " << outcome.code;
  EXPECT_EQ(outcome.report, latest + ": write failed: " + std::strerror(EFBIG));
  EXPECT_FALSE(leaves_temporary(latest));
  EXPECT_EQ(first_weight_of_run(dir), 2.f);
  fs::rename(previous_checkpoint_for(latest), latest);
  EXPECT_EQ(first_weight_of_run(dir), 1.f);
}

TEST(RunDir, ATruncatedCheckpointIsOneLineNamingIt) {
  const std::string dir = run_dir("truncated"), latest = run_checkpoint(dir);
  checkpoint_agent(dir, 1);
  fs::resize_file(latest, fs::file_size(latest) / 2);
  try {
    first_weight_of_run(dir);
    FAIL() << "a truncated checkpoint loaded";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), latest + ": damaged checkpoint (truncated: no zip directory at the end)");
  }
}

TEST(RunDir, AFlippedByteAmongTheWeightsIsCaughtBeforeLibTorchLoadsIt) {
  const std::string dir = run_dir("flipped"), latest = run_checkpoint(dir);
  checkpoint_agent(dir, 1.5f);
  std::string bytes = read_file(latest);
  const float weight = 1.5f;
  const std::string run_of_weights = std::string(reinterpret_cast<const char*>(&weight), 4) + std::string(
                                         reinterpret_cast<const char*>(&weight), 4);
  const size_t at = bytes.find(run_of_weights);
  ASSERT_NE(at, std::string::npos);
  bytes[at + 2] ^= 0x01;  // 1.5 becomes another float: LibTorch alone would load it
  write_file_atomically(latest, bytes);
  try {
    first_weight_of_run(dir);
    FAIL() << "a checkpoint with a changed weight loaded";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(latest + ": damaged checkpoint (entry ", 0), 0u) << message;
    EXPECT_NE(message.find("fails its CRC-32)"), std::string::npos) << message;
  }
}

TEST(RunDir, ResumingFromATruncatedLatestTakesThePrevious) {
  const std::string dir = run_dir("resume"), latest = run_checkpoint(dir);
  checkpoint_agent(dir, 1);
  checkpoint_agent(dir, 2);
  fs::resize_file(latest, fs::file_size(latest) / 2);
  auto agent = agent_with_weights(0);
  const ResumedCheckpoint resumed = resume_checkpoint(latest, [&](const std::string& path) {
    torch::serialize::InputArchive root, archive;
    root.load_from(path);
    root.read("agent", archive);
    agent->load(archive);
  });
  EXPECT_EQ(resumed.path, previous_checkpoint_for(latest));
  EXPECT_EQ(agent->parameters().front().flatten()[0].item<float>(), 1.f);
}

}  // namespace
}  // namespace vaegail
