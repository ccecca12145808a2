#include "experts/gait_episode.h"

#include <chrono>
#include <cmath>
#include <vector>

#include "experts/balance_feedback.h"
#include "experts/gait_controller.h"
#include "util/rng.h"

namespace vaegail {

namespace {
constexpr std::uint64_t kGaitPushStream = 1;   // the pushes' stream of the episode's seed
constexpr std::uint64_t kGaitNoiseStream = 2;  // and the execution noise's
constexpr std::uint64_t kGaitLearnerStream = 3;  // and the learner's turns'
constexpr double kGaitTransientSeconds = 1.0;  // the start left out of the means

struct PelvisPush {
  double start = 0, end = 0;  // s since the reset
  double fx = 0, fy = 0;      // N, world frame
};

std::vector<PelvisPush> draw_pushes(const GaitEpisodeOptions& o) {
  Rng rng(derive_seed(o.seed, kGaitPushStream));
  std::vector<PelvisPush> pushes;
  for (int k = 0; k < o.pushes; ++k) {
    const double start = rng.uniform(o.push_earliest, o.push_latest), direction = rng.uniform(0, 2 * M_PI);
    pushes.push_back({start, start + o.push_duration, o.push_force * std::cos(direction), o.push_force * std::sin(direction)});
  }
  return pushes;
}

// The gait controller with the pushes applied to the pelvis at the physics steps they cover.
class PushedGait : public PhysicsStepController {
 public:
  PushedGait(GaitController& gait, int pelvis, std::vector<PelvisPush> pushes)
      : gait_(gait), pelvis_(pelvis), pushes_(std::move(pushes)) {}
  void control(const mjModel* m, mjData* d) override {
    gait_.control(m, d);
    double* force = d->xfrc_applied + 6 * pelvis_;
    force[0] = force[1] = 0;
    for (const auto& push : pushes_)
      if (d->time >= push.start && d->time < push.end) {
        force[0] += push.fx;
        force[1] += push.fy;
      }
  }

 private:
  GaitController& gait_;
  int pelvis_;
  std::vector<PelvisPush> pushes_;
};

// Another controller with Gaussian noise added to the ctrl it writes, redrawn by draw() (once per
// control step): DART's execution noise.
class NoisyControl : public PhysicsStepController {
 public:
  NoisyControl(PhysicsStepController& inner, int motors, double std, std::uint64_t seed)
      : inner_(inner), noise_(motors), std_(std), rng_(seed) {}
  void draw() {
    for (double& n : noise_) n = std_ * rng_.normal();
  }
  void control(const mjModel* m, mjData* d) override {
    inner_.control(m, d);
    for (int a = 0; a < m->nu; ++a) d->ctrl[a] += noise_[a];
  }

 private:
  PhysicsStepController& inner_;
  std::vector<double> noise_;
  double std_;
  Rng rng_;
};

// A learner's held action in place of the controller's ctrl; the controller (with its pushes)
// still runs first at every physics step, so that its state machine and filters follow the walk.
class LearnerControl : public PhysicsStepController {
 public:
  LearnerControl(PhysicsStepController& beneath, const float* action) : beneath_(beneath), action_(action) {}
  void control(const mjModel* m, mjData* d) override {
    beneath_.control(m, d);
    for (int a = 0; a < m->nu; ++a) d->ctrl[a] = action_[a];
  }

 private:
  PhysicsStepController& beneath_;
  const float* action_;
};

// Footholds' mean step length and width (in the frame of the heading at each landing) and
// cadence, over the steps that land after the transient.
void foothold_statistics(const std::vector<Foothold>& footholds, const GaitParameters& p, GaitEpisodeResult& r) {
  double length = 0, width = 0;
  int counted = 0;
  size_t first = 0;
  for (size_t k = 1; k < footholds.size(); ++k) {
    if (footholds[k].time < kGaitTransientSeconds) continue;
    if (counted == 0) first = k - 1;
    const Vec2 step = to_heading_frame({footholds[k].x - footholds[k - 1].x, footholds[k].y - footholds[k - 1].y},
                                       commanded_heading(p, footholds[k].time));
    length += step[0];
    width += std::abs(step[1]);
    ++counted;
  }
  if (counted == 0) return;
  r.step_length = length / counted;
  r.step_width = width / counted;
  r.cadence = 60.0 * counted / (footholds.back().time - footholds[first].time);
}
}  // namespace

GaitEpisodeResult run_gait_episode(HumanoidEnv& env, const GaitParameters& p, const GaitEpisodeOptions& o,
                                   const GaitStepObserver& observer) {
  const auto start = std::chrono::steady_clock::now();
  const GaitSkeleton skeleton(env.model(), "humanoid");
  env.reset(o.seed);
  GaitController gait(skeleton, p);
  PushedGait pushed(gait, skeleton.root, draw_pushes(o));
  const int steps = o.steps > 0 ? o.steps : env.episode_length();
  const int n_features = static_cast<int>(env.feature_names().size());
  Episode episode;  // the features, for the gait signature
  episode.features.resize(n_features);
  env.features(episode.features.data());
  const double* com = env.data()->subtree_com + 3 * skeleton.root;
  const Vec2 com_start = {com[0], com[1]};
  std::vector<float> action(env.act_dim()), label(env.act_dim());
  const bool noisy = o.action_noise > 0, dagger = o.learner && o.learner_share > 0, labelled = noisy || dagger;
  NoisyControl noisy_gait(pushed, env.act_dim(), o.action_noise, derive_seed(o.seed, kGaitNoiseStream));
  PhysicsStepController& executed = noisy ? static_cast<PhysicsStepController&>(noisy_gait) : pushed;
  std::vector<float> observation(env.obs_dim()), learner_action(env.act_dim());
  LearnerControl learner(executed, learner_action.data());
  Rng learner_turns(derive_seed(o.seed, kGaitLearnerStream));
  GaitEpisodeResult r;
  int measured = 0;
  if (observer) observer(env, nullptr, nullptr);
  for (int t = 0; t < steps && !r.fallen; ++t) {
    if (labelled) {
      GaitController clean = gait;  // its state machine and filters as they are now
      env.lookahead_controlled(clean, label.data());
    }
    if (noisy) noisy_gait.draw();
    const bool learner_acts = dagger && learner_turns.uniform(0, 1) < o.learner_share;
    if (learner_acts) {
      env.observe(observation.data());
      o.learner(observation.data(), learner_action.data());
    }
    const StepOutcome outcome = env.step_controlled(learner_acts ? static_cast<PhysicsStepController&>(learner) : executed,
                                                    action.data());
    episode.rewards.push_back(outcome.reward);
    episode.features.resize(episode.features.size() + n_features);
    env.features(episode.features.data() + episode.features.size() - n_features);
    if (observer) observer(env, labelled ? label.data() : action.data(), &outcome);
    ++r.control_steps;
    r.fallen = env.fallen();
    const double time = env.data()->time;
    r.final_heading_error = std::abs(std::remainder(env.heading() - commanded_heading(p, time), 2 * M_PI));
    for (float a : action) r.effort += static_cast<double>(a) * a / action.size();
    if (time < kGaitTransientSeconds) continue;
    ++measured;
    r.heading_error += r.final_heading_error;
    r.speed += env.forward_speed();
    r.pelvis_height += env.root_height();
    const StyleTerms style = env.style_measures();
    for (int k = 0; k < kStyleTerms; ++k) r.style[k] += style[k];
  }
  r.time_up = r.control_steps * env.control_timestep();
  r.effort /= r.control_steps;
  if (measured > 0) {
    r.heading_error /= measured;
    r.speed /= measured;
    r.pelvis_height /= measured;
    for (double& x : r.style) x /= measured;
  }
  const Vec2 moved = to_heading_frame({com[0] - com_start[0], com[1] - com_start[1]}, p.heading);
  r.distance = moved[0];
  r.lateral_drift = moved[1];
  r.steps = gait.state().steps();
  foothold_statistics(gait.footholds(), p, r);
  r.signature = gait_signature(episode, env.feature_names(), env.control_timestep());
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

int held_mean_replay_steps(HumanoidEnv& env, const GaitParameters& p, const GaitEpisodeOptions& options,
                           double tolerance) {
  GaitEpisodeOptions unpushed = options;
  unpushed.pushes = 0;
  const int root = mj_name2id(env.model(), mjOBJ_BODY, "root");
  std::vector<std::vector<float>> actions;
  std::vector<Vec3> path;
  run_gait_episode(env, p, unpushed, [&](const HumanoidEnv& e, const float* action, const StepOutcome*) {
    if (!action) return;  // the reset
    actions.emplace_back(action, action + e.act_dim());
    const double* x = e.data()->xpos + 3 * root;
    path.push_back({x[0], x[1], x[2]});
  });
  env.reset(options.seed);
  for (size_t t = 0; t < actions.size(); ++t) {
    env.step(actions[t].data());
    const double* x = env.data()->xpos + 3 * root;
    const double off = std::sqrt(std::pow(x[0] - path[t][0], 2) + std::pow(x[1] - path[t][1], 2) + std::pow(x[2] - path[t][2], 2));
    if (off > tolerance || env.fallen()) return static_cast<int>(t) + 1;
  }
  return static_cast<int>(actions.size());
}

}  // namespace vaegail
