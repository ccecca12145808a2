#include "gail/weights_export.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "env/walker.h"
#include "gail/bc_agent.h"
#include "gail/behavior_cloning.h"
#include "gail/diverse_gail.h"
#include "gail/test_support.h"
#include "util/checkpoint_file.h"
#include "util/test_error.h"
#include "util/test_small_fs.h"
#include "vae/toy_trajectories.h"
#include "vae/trained_vae.h"
#include "vae/vae_trainer.h"

namespace vaegail {
namespace {

namespace fs = std::filesystem;

class WeightsExportTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = fs::temp_directory_path() / ("weights_export_test_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  void TearDown() override { fs::remove_all(dir); }

  std::string path(const std::string& name) const { return (dir / name).string(); }

  fs::path dir;
};

// The top-level entries of a LibTorch archive that `names` lists.
std::vector<std::string> entries_among(const std::string& file, const std::vector<std::string>& names) {
  torch::serialize::InputArchive archive;
  archive.load_from(file);
  std::vector<std::string> found;
  c10::IValue value;
  torch::serialize::InputArchive sub;
  for (const auto& name : names)
    if (archive.try_read(name, value) || archive.try_read(name, sub)) found.push_back(name);
  return found;
}

TEST_F(WeightsExportTest, AVaeExportEncodesAndActsExactlyAsItsCheckpointWithoutTheOptimiser) {
  const auto [states, actions] = vae::testing::toy_trajectories(5, 7, 3, 2, 3);
  vae::TrainerOptions options;
  options.run_dir = path("vae");
  options.epochs = 2;
  options.progress = false;
  vae::VaeTrainer(vae::testing::tiny_vae_config(3, 2), options, {states, actions, {}}, {}).train();

  const std::string weights = path("vae/weights.pt");
  EXPECT_EQ(export_weights(options.run_dir, weights), "vae");
  const std::string checkpoint = options.run_dir + "/checkpoints/latest.pt";
  EXPECT_EQ(entries_among(checkpoint, {"kind", "config", "model", "optimizer"}),
            (std::vector<std::string>{"config", "model", "optimizer"}));
  EXPECT_EQ(entries_among(weights, {"kind", "config", "model", "optimizer"}),
            (std::vector<std::string>{"kind", "config", "model"}));
  EXPECT_LT(fs::file_size(weights), fs::file_size(checkpoint) / 2);  // Adam keeps two moments per weight

  auto trained = vae::load_trained_vae(checkpoint), exported = vae::load_trained_vae(weights);
  trained->eval();
  exported->eval();
  EXPECT_EQ(exported->config().to_json(), trained->config().to_json());
  const auto [mu, sigma] = vae::encode(trained, states);
  const auto [mu2, sigma2] = vae::encode(exported, states);
  EXPECT_TRUE(torch::equal(mu, mu2));
  EXPECT_TRUE(torch::equal(sigma, sigma2));
  torch::NoGradGuard no_grad;
  const auto x = states.select(1, 2);
  EXPECT_TRUE(torch::equal(exported->action_mean(x, mu), trained->action_mean(x, mu)));

  // The run directory alone: its checkpoint while there is one, then the weights file it ships.
  auto from_dir = vae::load_trained_vae(options.run_dir);
  EXPECT_TRUE(torch::equal(vae::encode(from_dir, states).first, mu));
  fs::remove_all(options.run_dir + "/checkpoints");
  from_dir = vae::load_trained_vae(options.run_dir);
  EXPECT_TRUE(torch::equal(vae::encode(from_dir, states).first, mu));
}

TEST_F(WeightsExportTest, GailAndBcExportsActExactlyAsTheirCheckpointsAndCarryTheirVae) {
  WalkerOptions w;
  w.episode_length = 8;
  const WalkerEnv env(w);
  const DemoSet demos = random_walker_demos(env, 6);
  torch::manual_seed(2);
  const vae::TrajectoryVae model(tiny_vae_config(env.obs_dim(), env.act_dim()));
  GailOptions options;
  options.iterations = 2;
  options.num_envs = 2;
  options.policy_hidden = options.critic_hidden = {16};
  options.discriminator_hidden = {8};
  // A run that records no VAE path: the export is told the VAE, here by its own weights file.
  GailTrainer(demos, model, env, options, path("diverse")).train();
  EXPECT_NE(one_line_error_of([&] { export_weights(path("diverse"), path("diverse.pt")); }).find("pass --vae"),
            std::string::npos);
  vae::save_vae_weights(model, path("vae.pt"));
  EXPECT_EQ(export_weights(path("diverse"), path("diverse.pt"), path("vae.pt")), "gail");
  options.mode = GailMode::Plain;
  GailTrainer(demos, vae::TrajectoryVae(nullptr), env, options, path("plain")).train();
  EXPECT_EQ(export_weights(path("plain"), path("plain.pt")), "gail");
  BcOptions bc;
  bc.hidden = {16};
  bc.epochs = 2;
  train_bc(demos, bc, path("bc"));
  EXPECT_EQ(export_weights(path("bc"), path("bc.pt")), "bc");

  torch::manual_seed(5);
  const auto obs = torch::randn({4, env.obs_dim()}), z = torch::randn({4, 2});
  const auto expect_same_actions = [&](const std::shared_ptr<Agent>& trained, const std::shared_ptr<Agent>& exported) {
    torch::NoGradGuard no_grad;
    EXPECT_TRUE(torch::equal(agent_mean_policy(exported)(obs, z), agent_mean_policy(trained)(obs, z)));
  };
  const int D = env.obs_dim(), A = env.act_dim();
  // The diverse run's weights file needs no VAE: it sizes the VAE itself and holds its weights.
  const vae::TrajectoryVae fresh(tiny_vae_config(D, A));
  expect_same_actions(load_gail_agent(path("diverse"), D, A, fresh, torch::kCPU),
                      load_gail_agent(path("diverse.pt"), D, A, vae::TrajectoryVae(nullptr), torch::kCPU));
  EXPECT_EQ(entries_among(path("diverse.pt"), {"kind", "config", "vae_config", "agent", "discriminator"}),
            (std::vector<std::string>{"kind", "config", "vae_config", "agent"}));
  expect_same_actions(load_gail_agent(path("plain"), D, A, vae::TrajectoryVae(nullptr), torch::kCPU),
                      load_gail_agent(path("plain.pt"), D, A, vae::TrajectoryVae(nullptr), torch::kCPU));
  expect_same_actions(load_bc_agent(path("bc"), D, A, torch::kCPU), load_bc_agent(path("bc.pt"), D, A, torch::kCPU));
  EXPECT_LT(fs::file_size(path("plain.pt")), fs::file_size(path("plain/checkpoints/latest.pt")));
}

// `vaegail export` onto a full file system: refused in one line, the export before kept.
TEST_F(WeightsExportTest, AnExportOnAFullDiskIsRefusedAndTheOneBeforeStillLoads) {
  SmallFileSystem small(512 * 1024);
  if (!small.mounted()) GTEST_SKIP() << small.why_not();
  WalkerOptions w;
  w.episode_length = 8;
  const WalkerEnv env(w);
  BcOptions bc;
  bc.hidden = {16};
  bc.epochs = 1;
  train_bc(random_walker_demos(env, 4), bc, path("bc"));
  const std::string weights = small.path("bc.pt");
  expect_refused_on_a_full_disk_then_saved(small, weights, [&] { export_weights(path("bc"), weights); });
  load_bc_agent(weights, env.obs_dim(), env.act_dim(), torch::kCPU);
}

TEST_F(WeightsExportTest, ABadWeightsFileIsOneLineNamingIt) {
  AgentOptions a;
  a.obs_dim = 3;
  a.act_dim = 2;
  a.policy_hidden = a.critic_hidden = {8};
  const std::string weights = path("bc.pt");
  save_agent_weights(weights, "bc", BcOptions{}, *Agent::make_gaussian(a));
  EXPECT_EQ(one_line_error_of([&] { load_gail_agent(weights, 3, 2, vae::TrajectoryVae(nullptr), torch::kCPU); }),
            weights + ": the weights of a bc run, not of a gail run");
  EXPECT_EQ(one_line_error_of([&] { vae::load_trained_vae(weights); }),
            weights + ": the weights of a bc run, not of a VAE");
  fs::resize_file(weights, fs::file_size(weights) / 2);
  EXPECT_EQ(one_line_error_of([&] { load_bc_agent(weights, 3, 2, torch::kCPU); }),
            weights + ": damaged checkpoint (truncated: no zip directory at the end)");
  EXPECT_EQ(one_line_error_of([&] { export_weights(path("nothing"), path("out.pt")); }),
            path("nothing") + "/config.json: no such file (not a run directory?)");
  EXPECT_FALSE(fs::exists(path("out.pt")));
}

}  // namespace
}  // namespace vaegail
