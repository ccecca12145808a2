#include "vaegail/controller.h"

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>
#include <torch/torch.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "env/walker.h"
#include "gail/bc_agent.h"
#include "gail/gail_agent.h"
#include "gail/weights_export.h"
#include "util/test_error.h"
#include "vae/trained_vae.h"

namespace vaegail {
namespace {

const std::string kSource = VAEGAIL_SOURCE_DIR;
const std::string kVae = kSource + "/checkpoints/walker/vae/checkpoints/latest.pt";
const std::string kDiverseGail = kSource + "/checkpoints/walker/diverse_gail";
const std::string kPlainGail = kSource + "/checkpoints/walker/plain_gail";
const std::string kBc = kSource + "/checkpoints/walker/bc";

// A fixed, varied action sequence: step t of a few seconds of flailing.
std::vector<float> flail(int t) {
  std::vector<float> a(6);
  for (int j = 0; j < 6; ++j) a[j] = static_cast<float>(1.2 * std::sin(0.3 * t + j));  // beyond ctrlrange too
  return a;
}

// The walker's observations x_1 .. x_{steps+1} of one episode: [steps + 1, 18].
torch::Tensor walker_states(int steps, std::uint64_t seed) {
  WalkerEnv env;
  env.reset(seed);
  std::vector<float> states = env.observation();
  for (int t = 0; t < steps; ++t) {
    env.step(flail(t).data());
    const auto obs = env.observation();
    states.insert(states.end(), obs.begin(), obs.end());
  }
  return torch::tensor(states).view({steps + 1, env.obs_dim()});
}

std::vector<float> to_vector(const torch::Tensor& t) {
  const auto c = t.to(torch::kFloat32).contiguous().view({-1});
  return {c.data_ptr<float>(), c.data_ptr<float>() + c.numel()};
}

// The controller's action for observation row `row` of states and z, against the policy's own.
void expect_acts_as(Controller& controller, const vae::LatentPolicy& policy, const torch::Tensor& states,
                    const torch::Tensor& z) {
  torch::NoGradGuard no_grad;
  for (int64_t row : {0, 7, 19}) {
    const auto obs = states[row].unsqueeze(0);
    const auto z_row = z.view({1, -1});
    EXPECT_EQ(controller.act(to_vector(obs), to_vector(z_row)), to_vector(policy(obs, z_row))) << "row " << row;
  }
}

TEST(Controller, VaePolicyActsAsTheVaeMeanPolicy) {
  auto controller = Controller::load_vae(kVae, "walker");
  EXPECT_EQ(controller.obs_dim(), 18);
  EXPECT_EQ(controller.act_dim(), 6);
  EXPECT_EQ(controller.latent_dim(), 20);
  EXPECT_DOUBLE_EQ(controller.control_timestep(), 0.025);
  const auto states = walker_states(20, 1);
  torch::manual_seed(0);
  expect_acts_as(controller, vae::vae_mean_policy(vae::load_trained_vae(kVae), torch::kCPU), states,
                 torch::randn({20}));
}

TEST(Controller, EmbedIsThePosteriorMeanOfTheDemonstration) {
  auto controller = Controller::load_vae(kVae, "walker");
  auto model = vae::load_trained_vae(kVae);
  model->eval();
  const auto a = walker_states(40, 1), b = walker_states(40, 2);
  const auto z_a = controller.embed(to_vector(a));
  EXPECT_EQ(z_a, to_vector(vae::encode(model, a.unsqueeze(0)).first));
  EXPECT_NE(z_a, controller.embed(to_vector(b)));  // it reads the states
}

TEST(Controller, DiverseGailActsAsTheRunsAgentAndEmbedsWithItsVae) {
  auto controller = Controller::load_gail(kDiverseGail, "walker", kVae);
  EXPECT_EQ(controller.latent_dim(), 20);
  auto vae_model = vae::load_trained_vae(kVae);
  const auto agent = load_gail_agent(kDiverseGail, 18, 6, vae_model, torch::kCPU);
  const auto states = walker_states(20, 3);
  const auto z = torch::tensor(controller.embed(to_vector(states)));
  expect_acts_as(controller, agent_mean_policy(agent), states, z);
  // The fine-tuned policy is not the VAE's own (the residual moved it).
  auto vae_controller = Controller::load_vae(kVae, "walker");
  EXPECT_NE(controller.act(to_vector(states[5]), to_vector(z)), vae_controller.act(to_vector(states[5]), to_vector(z)));
}

TEST(Controller, PlainGailAndBcTakeNoEmbedding) {
  const auto states = walker_states(20, 4);
  const auto none = torch::zeros({0});
  auto plain = Controller::load_gail(kPlainGail, "walker");
  EXPECT_EQ(plain.latent_dim(), 0);
  EXPECT_TRUE(plain.embed(to_vector(states)).empty());
  expect_acts_as(plain, agent_mean_policy(load_gail_agent(kPlainGail, 18, 6, vae::TrajectoryVae(nullptr), torch::kCPU)),
                 states, none);
  auto bc = Controller::load_bc(kBc, "walker");
  EXPECT_EQ(bc.latent_dim(), 0);
  expect_acts_as(bc, agent_mean_policy(load_bc_agent(kBc, 18, 6, torch::kCPU)), states, none);
}

// Two controllers of one policy: the same embedding and the same actions, bit for bit.
void expect_same_policy(Controller& a, Controller& b, const torch::Tensor& states) {
  const auto z = a.embed(to_vector(states));
  EXPECT_EQ(b.embed(to_vector(states)), z);
  for (int64_t row : {0, 7, 19}) EXPECT_EQ(b.act(to_vector(states[row]), z), a.act(to_vector(states[row]), z)) << row;
}

TEST(Controller, ThePublishedRunsExportedActAndEmbedExactlyAsTheirCheckpoints) {
  const std::string dir = ::testing::TempDir() + "controller_exports_" + std::to_string(::getpid());
  std::filesystem::create_directories(dir);
  const std::string vae_run = kSource + "/checkpoints/walker/vae";
  export_weights(vae_run, dir + "/vae.pt");
  export_weights(kDiverseGail, dir + "/diverse.pt", kVae);
  export_weights(kPlainGail, dir + "/plain.pt");
  export_weights(kBc, dir + "/bc.pt");
  const auto states = walker_states(20, 5);
  auto vae = Controller::load_vae(vae_run, "walker"), vae_weights = Controller::load_vae(dir + "/vae.pt", "walker");
  expect_same_policy(vae, vae_weights, states);
  // The diverse run's weights file holds its VAE's sizes and weights: no VAE checkpoint is given.
  auto diverse = Controller::load_gail(kDiverseGail, "walker", kVae),
       diverse_weights = Controller::load_gail(dir + "/diverse.pt", "walker");
  EXPECT_EQ(diverse_weights.latent_dim(), 20);
  expect_same_policy(diverse, diverse_weights, states);
  auto plain = Controller::load_gail(kPlainGail, "walker"),
       plain_weights = Controller::load_gail(dir + "/plain.pt", "walker");
  expect_same_policy(plain, plain_weights, states);
  auto bc = Controller::load_bc(kBc, "walker"), bc_weights = Controller::load_bc(dir + "/bc.pt", "walker");
  expect_same_policy(bc, bc_weights, states);
  std::filesystem::remove_all(dir);
}

TEST(Controller, ObservesAUserSimulationAsTheTrainingTaskDoes) {
  auto controller = Controller::load_vae(kVae, "walker");
  WalkerEnv env;
  env.reset(6);
  // The user's own model and data, in the environment's initial state.
  char error[500] = "";
  mjModel* m = mj_loadXML((kSource + "/models/walker.xml").c_str(), nullptr, error, sizeof error);
  ASSERT_NE(m, nullptr) << error;
  mjData* d = mj_makeData(m);
  mj_copyData(d, m, env.data());
  const int frame_skip = static_cast<int>(std::lround(controller.control_timestep() / m->opt.timestep));
  for (int t = 0; t < 30; ++t) {
    EXPECT_EQ(controller.observe(m, d), env.observation()) << "step " << t;
    const auto action = flail(t);
    env.step(action.data());
    for (int a = 0; a < m->nu; ++a) d->ctrl[a] = action[a];  // unclamped: MuJoCo clamps as the env did
    for (int k = 0; k < frame_skip; ++k) mj_step(m, d);
  }
  mj_deleteData(d);
  mj_deleteModel(m);
}

TEST(Controller, BadInputsAreOneLineErrorsNamingWhat) {
  auto controller = Controller::load_vae(kVae, "walker");
  EXPECT_NE(one_line_error_of([&] { controller.act(std::vector<float>(17), std::vector<float>(20)); })
                .find("the observation has 17 values, the policy takes 18"),
            std::string::npos);
  EXPECT_NE(one_line_error_of([&] { controller.act(std::vector<float>(18), {}); }).find("z has 0 values"),
            std::string::npos);
  EXPECT_NE(one_line_error_of([&] { controller.embed(std::vector<float>(20)); }).find("not a positive multiple"),
            std::string::npos);
  EXPECT_NE(one_line_error_of([] { Controller::load_vae("/nonexistent/latest.pt", "walker"); })
                .find("/nonexistent/latest.pt"),
            std::string::npos);
  EXPECT_NE(one_line_error_of([] { Controller::load_vae(kVae, "arm"); }).find("task 'arm'"), std::string::npos);
  EXPECT_NE(one_line_error_of([] { Controller::load_bc("/nonexistent/run", "walker"); }).find("/nonexistent/run"),
            std::string::npos);
}

}  // namespace
}  // namespace vaegail
