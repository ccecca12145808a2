#include "rl/agent.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "rl/test_support.h"
#include "util/test_small_fs.h"

namespace vaegail {
namespace {

AgentOptions small_agent() {
  AgentOptions o;
  o.obs_dim = 3;
  o.condition_dim = 2;
  o.act_dim = 2;
  o.policy_hidden = o.critic_hidden = {8};
  return o;
}

TEST(Agent, InputIsTheNormalisedObservationFollowedByTheCondition) {
  auto agent = Agent::make_gaussian(small_agent());
  agent->normalizer().update(torch::tensor({{0.f, 0.f, 0.f}, {2.f, 4.f, 6.f}}));  // mean (1,2,3), std (1,2,3)
  const auto input = agent->input(torch::tensor({{2.f, 2.f, 0.f}}), torch::tensor({{7.f, 8.f}}));
  EXPECT_TRUE(torch::allclose(input, torch::tensor({{1.f, 0.f, -1.f, 7.f, 8.f}}), 1e-5, 1e-5));
  EXPECT_EQ(agent->condition_dim(), 2);
}

TEST(Agent, CheckpointRestoresPolicyCriticAndNormaliser) {
  const auto path = (std::filesystem::temp_directory_path() / "vaegail_rl_agent_test.pt").string();
  auto saved = Agent::make_gaussian(small_agent());
  saved->normalizer().update(torch::randn({10, 3}) * 5 + 1);
  saved->save_checkpoint(path);

  torch::manual_seed(123);  // the fresh agent's initial weights differ from the saved ones
  auto loaded = Agent::make_gaussian(small_agent());
  loaded->load_checkpoint(path);
  std::filesystem::remove(path);

  const auto input = loaded->input(torch::randn({4, 3}), torch::randn({4, 2}));
  EXPECT_TRUE(torch::equal(saved->input(torch::ones({1, 3}), torch::ones({1, 2})),
                           loaded->input(torch::ones({1, 3}), torch::ones({1, 2}))));
  EXPECT_TRUE(torch::equal(saved->policy().distribution(input).mean, loaded->policy().distribution(input).mean));
  EXPECT_TRUE(torch::equal(saved->critic().forward(input), loaded->critic().forward(input)));
  EXPECT_DOUBLE_EQ(loaded->normalizer().count(), 10.0);
}

// An expert's checkpoint (PPO) on a full file system: refused in one line, the one before kept.
TEST(Agent, ACheckpointOnAFullDiskIsRefusedAndTheOneBeforeStillLoads) {
  SmallFileSystem small(512 * 1024);
  if (!small.mounted()) GTEST_SKIP() << small.why_not();
  const std::string path = small.path("agent.pt");
  auto agent = Agent::make_gaussian(small_agent());
  expect_refused_on_a_full_disk_then_saved(small, path, [&] { agent->save_checkpoint(path); });
  Agent::make_gaussian(small_agent())->load_checkpoint(path);
}

}  // namespace
}  // namespace vaegail
