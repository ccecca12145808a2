#include "env/generic_task.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace vaegail {

namespace {

const std::string kPrefix = "vaegail_", kContextPrefix = "vaegail_context_";

// The value of <numeric name="name">, or `fallback` when the MJCF has none.
double custom_number(const MujocoModel& model, const std::string& name, double fallback) {
  const mjModel* m = model.get();
  const int i = mj_name2id(m, mjOBJ_NUMERIC, name.c_str());
  if (i < 0) return fallback;
  if (m->numeric_size[i] != 1)
    throw std::runtime_error(model.source() + ": <numeric name=\"" + name + "\"> must hold one value");
  return m->numeric_data[m->numeric_adr[i]];
}

int custom_count(const MujocoModel& model, const std::string& name, int fallback) {
  const double v = custom_number(model, name, fallback);
  if (!(v >= 1) || v != std::floor(v) || v > 1e9)
    throw std::runtime_error(model.source() + ": <numeric name=\"" + name + "\"> must be a whole number >= 1");
  return static_cast<int>(v);
}

std::string custom_text(const MujocoModel& model, const std::string& name) {
  const mjModel* m = model.get();
  const int i = mj_name2id(m, mjOBJ_TEXT, name.c_str());
  return i < 0 ? std::string() : std::string(m->text_data + m->text_adr[i]);
}

MujocoEnvOptions base_options(const MujocoModel& model, const GenericTaskOptions& o) {
  MujocoEnvOptions base;
  base.id = model.source();
  base.frame_skip = o.frame_skip > 0            ? o.frame_skip
                    : o.control_timestep > 0    ? static_cast<int>(std::lround(o.control_timestep / model.get()->opt.timestep))
                                                : custom_count(model, kPrefix + "frame_skip", 1);
  if (base.frame_skip < 1)
    throw std::runtime_error(model.source() + ": a control step of " + std::to_string(o.control_timestep) +
                             " s is shorter than the physics step");
  base.episode_length = o.episode_length > 0 ? o.episode_length : custom_count(model, kPrefix + "episode_length", 1000);
  return base;
}

}  // namespace

GenericTaskEnv::GenericTaskEnv(std::shared_ptr<const MujocoModel> model, GenericTaskOptions options)
    : MujocoEnv(model, base_options(*model, options)), options_generic_(std::move(options)) {
  const mjModel* m = model_->get();
  feature_names_ = {"com_speed"};
  const std::string fall_body = custom_text(*model_, kPrefix + "fall_body");
  if (!fall_body.empty()) {
    fall_body_ = model_->id(mjOBJ_BODY, fall_body);
    fall_height_ = custom_number(*model_, kPrefix + "fall_height", 0.0);
    feature_names_.push_back(fall_body + "_height");
    feature_names_.push_back("fallen");
  }
  for (int s = 0; s < m->nsensor; ++s) {
    const char* name = mj_id2name(m, mjOBJ_SENSOR, s);
    if (!name || !*name) continue;
    for (int k = 0; k < m->sensor_dim[s]; ++k) {
      feature_names_.push_back("sensor:" + std::string(name) +
                               (m->sensor_dim[s] > 1 ? "[" + std::to_string(k) + "]" : ""));
      sensor_values_.push_back(m->sensor_adr[s] + k);
    }
  }
  for (int s = 0; s < m->nsite; ++s) {
    const char* name = mj_id2name(m, mjOBJ_SITE, s);
    if (!name || !*name) continue;
    for (int k = 0; k < 3; ++k) {
      feature_names_.push_back("site:" + std::string(name) + ":" + "xyz"[k]);
      site_values_.push_back(3 * s + k);
    }
  }
  for (int i = 0; i < m->nnumeric; ++i) {
    const std::string name = mj_id2name(m, mjOBJ_NUMERIC, i);
    if (name.rfind(kContextPrefix, 0) != 0) continue;
    context_names_.push_back(name.substr(kContextPrefix.size()));
    context_.push_back(custom_number(*model_, name, 0.0));
  }
  for (const auto& name : options_generic_.context_names)
    if (std::find(context_names_.begin(), context_names_.end(), name) == context_names_.end()) {
      context_names_.push_back(name);
      context_.push_back(0.0);
    }
}

void GenericTaskEnv::initialize_episode(Rng& rng) {
  if (model_->get()->nkey > 0) mj_resetDataKeyframe(model_->get(), mutable_data(), 0);
  MujocoEnv::initialize_episode(rng);
}

StepOutcome GenericTaskEnv::step(const float* action) {
  const StepOutcome out = MujocoEnv::step(action);
  // mj_step computes sensors before it integrates: recompute them for the state it reached.
  if (!sensor_values_.empty()) mj_forward(model_->get(), mutable_data());
  return out;
}

bool GenericTaskEnv::fallen() const { return fall_body_ >= 0 && data()->xpos[3 * fall_body_ + 2] < fall_height_; }

void GenericTaskEnv::features(double* out) const {
  double v[3];
  subtree_velocity(model_->get()->nbody > 1 ? 1 : 0, v);
  *out++ = v[0];
  if (fall_body_ >= 0) {
    *out++ = data()->xpos[3 * fall_body_ + 2];
    *out++ = fallen() ? 1.0 : 0.0;
  }
  for (int i : sensor_values_) *out++ = data()->sensordata[i];
  for (int i : site_values_) *out++ = data()->site_xpos[i];
}

std::unique_ptr<Env> GenericTaskEnv::clone() const {
  GenericTaskOptions o = options_generic_;
  o.frame_skip = options_.frame_skip;
  o.episode_length = options_.episode_length;
  auto copy = std::make_unique<GenericTaskEnv>(model_, o);
  copy->set_context(context_);
  return copy;
}

}  // namespace vaegail
