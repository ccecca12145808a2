// One-shot imitation in your own MuJoCo loop: embed one demonstration of the walker, start the
// model where the demonstration started, let the trained policy walk it for one episode, and
// compare its speed with the demonstration's. Uses the plain MuJoCo C API and
// vaegail/controller.h, nothing else.
//
//   walker_controller MODEL.xml DEMO.txt VAE_CHECKPOINT [GAIL_RUN_DIR]
//
// DEMO.txt: one observation per line (the walker's 18 values, src/env/walker.h), x_1 .. x_{T+1}
// of one demonstration; lines starting with '#' are comments. With GAIL_RUN_DIR the policy is
// that fine-tuned diverse-GAIL run's (on the VAE of VAE_CHECKPOINT), else the VAE's own.
#include <mujoco/mujoco.h>
#include <vaegail/controller.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

constexpr int kEpisodeSteps = 400;   // the walker task's 10 s episode
constexpr int kRootxVel = 9;         // observation index of the forward velocity (m/s)
constexpr double kFallHeight = 0.7;  // the task's fall rule: torso centre below 0.7 m ...
constexpr double kFallCosPitch = 0.54;  // ... or pitched more than ~57 degrees

// The demonstration's observations, row after row; throws naming the file and the line.
std::vector<float> read_states(const std::string& path, int obs_dim) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open");
  std::vector<float> states;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    const std::vector<float> row{std::istream_iterator<float>(fields), std::istream_iterator<float>()};
    if (static_cast<int>(row.size()) != obs_dim)
      throw std::runtime_error(path + ":" + std::to_string(number) + ": " + std::to_string(row.size()) +
                               " values, the walker observes " + std::to_string(obs_dim));
    states.insert(states.end(), row.begin(), row.end());
  }
  if (states.empty()) throw std::runtime_error(path + ": no states");
  return states;
}

// Puts the walker in the state an observation describes (src/env/walker.h's layout: torso height,
// pitch as sin/cos, six joint angles, root velocities, six joint velocities), at x = 0. The torso
// is the body the root joints move, so its height is its rest height 1.3 m plus the rootz slide.
void set_walker_state(const mjModel* m, mjData* d, const float* obs) {
  mj_resetData(m, d);
  d->qpos[0] = 0;
  d->qpos[1] = obs[0] - 1.3;
  d->qpos[2] = std::atan2(obs[1], obs[2]);
  for (int j = 0; j < 6; ++j) d->qpos[3 + j] = obs[3 + j];
  for (int k = 0; k < 9; ++k) d->qvel[k] = obs[9 + k];
  mj_forward(m, d);
}

double mean_column(const std::vector<float>& rows, int width, int column) {
  double sum = 0;
  const size_t n = rows.size() / width;
  for (size_t r = 0; r < n; ++r) sum += rows[r * width + column];
  return sum / n;
}

int run(int argc, char** argv) {
  if (argc < 4 || argc > 5) {
    std::fprintf(stderr, "usage: %s MODEL.xml DEMO.txt VAE_CHECKPOINT [GAIL_RUN_DIR]\n", argv[0]);
    return 2;
  }
  const std::string model_path = argv[1], demo_path = argv[2], vae_path = argv[3];
  vaegail::Controller controller = argc == 5 ? vaegail::Controller::load_gail(argv[4], "walker", vae_path)
                                             : vaegail::Controller::load_vae(vae_path, "walker");

  char error[1000] = "";
  mjModel* m = mj_loadXML(model_path.c_str(), nullptr, error, sizeof error);
  if (!m) throw std::runtime_error(model_path + ": " + error);
  mjData* d = mj_makeData(m);
  const int frame_skip = static_cast<int>(std::lround(controller.control_timestep() / m->opt.timestep));

  const std::vector<float> demo = read_states(demo_path, controller.obs_dim());
  const std::vector<float> z = controller.embed(demo);
  std::printf("demonstration: %zu states, mean forward speed %.2f m/s; z has %zu values\n",
              demo.size() / controller.obs_dim(), mean_column(demo, controller.obs_dim(), kRootxVel), z.size());

  set_walker_state(m, d, demo.data());  // as the paper's one-shot imitation starts
  const double start_x = d->qpos[0];
  double speed_sum = 0, act_seconds = 0;
  int steps = 0;
  std::vector<float> obs = controller.observe(m, d);
  const auto fallen = [&] { return obs[0] < kFallHeight || obs[2] < kFallCosPitch; };
  while (steps < kEpisodeSteps && !fallen()) {
    const auto start = std::chrono::steady_clock::now();
    const std::vector<float> action = controller.act(obs, z);
    act_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    for (int a = 0; a < m->nu; ++a) d->ctrl[a] = action[a];
    for (int k = 0; k < frame_skip; ++k) mj_step(m, d);
    ++steps;
    obs = controller.observe(m, d);
    speed_sum += obs[kRootxVel];
  }
  std::printf("policy: %d steps (%.1f s)%s, distance %.2f m, mean forward speed %.2f m/s\n", steps,
              steps * controller.control_timestep(), fallen() ? ", fell" : ", did not fall", d->qpos[0] - start_x,
              speed_sum / steps);
  std::printf("act(): %.0f us per call\n", 1e6 * act_seconds / steps);
  mj_deleteData(d);
  mj_deleteModel(m);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "walker_controller: error: %s\n", e.what());
    return 1;
  }
}
