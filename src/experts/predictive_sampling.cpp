#include "experts/predictive_sampling.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "env/mujoco_env.h"

namespace vaegail {

namespace {

std::unique_ptr<MujocoEnv> scratch_copy(const MujocoEnv& env) {
  std::unique_ptr<Env> copy = env.clone();
  auto* mujoco = dynamic_cast<MujocoEnv*>(copy.get());
  if (!mujoco) throw std::logic_error("predictive sampling: the environment's clone is not a MuJoCo environment");
  copy.release();
  return std::unique_ptr<MujocoEnv>(mujoco);
}

}  // namespace

PredictiveSampling::PredictiveSampling(const MujocoEnv& env, PredictiveSamplingOptions options)
    : options_(options), act_dim_(env.act_dim()), scratch_(scratch_copy(env)), rng_(options.seed) {
  if (options_.samples < 1 || options_.horizon < 2 || options_.knots < 2 || options_.noise < 0)
    throw std::invalid_argument("predictive sampling: needs samples >= 1, horizon >= 2, knots >= 2, noise >= 0");
  reset();
}

PredictiveSampling::~PredictiveSampling() = default;

void PredictiveSampling::reset() { plan_.assign(static_cast<size_t>(options_.knots) * act_dim_, 0.0f); }

double PredictiveSampling::spacing() const {
  return static_cast<double>(options_.horizon - 1) / (options_.knots - 1);
}

void PredictiveSampling::plan_action(const std::vector<float>& plan, int knots, int act_dim, double spacing,
                                     double t, float* out) {
  const double s = std::clamp(t / spacing, 0.0, static_cast<double>(knots - 1));
  const int k = std::min(static_cast<int>(s), knots - 2);
  const double w = s - k;
  const float* a = plan.data() + static_cast<size_t>(k) * act_dim;
  const float* b = a + act_dim;
  for (int i = 0; i < act_dim; ++i) out[i] = static_cast<float>((1 - w) * a[i] + w * b[i]);
}

double PredictiveSampling::score(const MujocoEnv& env, const std::vector<float>& plan) {
  scratch_->set_context(env.context());
  scratch_->set_state(env.model(), env.data());
  std::vector<float> action(act_dim_);
  double total = 0;
  for (int t = 0; t < options_.horizon; ++t) {
    plan_action(plan, options_.knots, act_dim_, spacing(), t, action.data());
    const StepOutcome out = scratch_->step(action.data());
    total += out.reward + (shaping ? shaping(*scratch_) : 0.0);
    if (out.terminated) return total - options_.fall_penalty;
  }
  return total;
}

std::vector<float> PredictiveSampling::act(const MujocoEnv& env) {
  // The plan moves one control step on: its knots are re-read at their new times.
  std::vector<float> shifted(plan_.size());
  for (int k = 0; k < options_.knots; ++k)
    plan_action(plan_, options_.knots, act_dim_, spacing(), k * spacing() + 1, shifted.data() + k * act_dim_);

  std::vector<float> best = shifted, candidate(shifted.size());
  double best_score = score(env, shifted);
  for (int s = 1; s < options_.samples; ++s) {
    for (size_t i = 0; i < candidate.size(); ++i)
      candidate[i] = std::clamp(static_cast<float>(shifted[i] + options_.noise * rng_.normal()), -1.0f, 1.0f);
    const double value = score(env, candidate);
    if (value > best_score) {
      best_score = value;
      best.swap(candidate);
    }
  }
  plan_ = std::move(best);
  std::vector<float> action(act_dim_);
  plan_action(plan_, options_.knots, act_dim_, spacing(), 0, action.data());
  return action;
}

}  // namespace vaegail
