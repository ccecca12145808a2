#include "experts/scripted_gait.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "util/rng.h"

namespace vaegail {

namespace {

const std::string kStylePrefix = "vaegail_gait_style_";
const int kStyleHead = 6;  // FREQUENCY KP KD PITCH_KP PITCH_KD LEAN, before the per-actuator triples

std::string actuator_name(const mjModel* m, int a) {
  const char* name = mj_id2name(m, mjOBJ_ACTUATOR, a);
  return name && *name ? name : "#" + std::to_string(a);
}

// The joint a motor drives; throws for anything else, as PD targets in radians need a hinge and
// a control that is a torque.
int motor_hinge(const mjModel* m, const std::string& model_name, int a) {
  const int joint = m->actuator_trnid[2 * a];
  const bool motor = m->actuator_gaintype[a] == mjGAIN_FIXED && m->actuator_biastype[a] == mjBIAS_NONE;
  if (m->actuator_trntype[a] != mjTRN_JOINT || m->jnt_type[joint] != mjJNT_HINGE || !motor)
    throw std::invalid_argument(model_name + ": actuator '" + actuator_name(m, a) +
                                "' is not a motor on a hinge joint (the scripted gait drives only those)");
  return joint;
}

bool about_y(const mjModel* m, int joint) { return std::abs(m->jnt_axis[3 * joint + 1]) > 0.999; }

// The first body with joints: the root the balance term reads the pitch of.
int root_body(const mjModel* m) {
  for (int b = 1; b < m->nbody; ++b)
    if (m->body_jntnum[b] > 0) return b;
  return -1;
}

// The root's hinge about y, or -1.
int root_pitch_joint(const mjModel* m, int root) {
  if (root < 0) return -1;
  for (int j = m->body_jntadr[root]; j < m->body_jntadr[root] + m->body_jntnum[root]; ++j)
    if (m->jnt_type[j] == mjJNT_HINGE && about_y(m, j)) return j;
  return -1;
}

// Half a joint's range and its centre (1 rad about 0 when unlimited).
std::pair<double, double> half_range_and_centre(const mjModel* m, int joint) {
  if (!m->jnt_limited[joint]) return {1.0, 0.0};
  const double lo = m->jnt_range[2 * joint], hi = m->jnt_range[2 * joint + 1];
  return {0.5 * (hi - lo), 0.5 * (hi + lo)};
}

GaitStyle style_from_custom(const mjModel* m, const std::string& model_name, int numeric) {
  const std::string name = mj_id2name(m, mjOBJ_NUMERIC, numeric);
  const int size = m->numeric_size[numeric];
  if (size != kStyleHead + 3 * m->nu)
    throw std::invalid_argument(model_name + ": <numeric name=\"" + name + "\"> holds " + std::to_string(size) +
                                " values; a style needs " + std::to_string(kStyleHead) + " + 3 per actuator = " +
                                std::to_string(kStyleHead + 3 * m->nu));
  const double* v = m->numeric_data + m->numeric_adr[numeric];
  GaitStyle s;
  s.name = name.substr(kStylePrefix.size());
  s.frequency = v[0];
  s.kp = v[1];
  s.kd = v[2];
  s.pitch_kp = v[3];
  s.pitch_kd = v[4];
  s.lean = v[5];
  for (const double* joint = v + kStyleHead; joint < v + size; joint += 3) {
    s.amplitude.push_back(joint[0]);
    s.offset.push_back(joint[1]);
    s.phase.push_back(joint[2]);
  }
  return s;
}

GaitStyle drawn_style(const mjModel* m, const std::string& model_name, const GaitKnobs& k, std::uint64_t seed,
                      int index) {
  Rng rng(derive_seed(seed, static_cast<std::uint64_t>(index)));
  GaitStyle s;
  s.name = "style" + std::to_string(index);
  s.frequency = rng.uniform(k.min_frequency, k.max_frequency);
  for (int a = 0; a < m->nu; ++a) {
    const auto [half, centre] = half_range_and_centre(m, motor_hinge(m, model_name, a));
    s.amplitude.push_back(half * rng.uniform(k.min_amplitude, k.max_amplitude));
    s.offset.push_back(centre + half * rng.uniform(-k.max_offset, k.max_offset));
    s.phase.push_back(rng.uniform(0, 2 * M_PI));
  }
  return s;
}

bool starts_with(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

}  // namespace

ScriptedGait::ScriptedGait(const mjModel* m, const std::string& model_name, std::vector<GaitStyle> styles)
    : styles_(std::move(styles)) {
  const int root = root_body(m), pitch = root_pitch_joint(m, root);
  if (pitch >= 0) {
    pitch_qpos_ = m->jnt_qposadr[pitch];
    pitch_qvel_ = m->jnt_dofadr[pitch];
  }
  for (int a = 0; a < m->nu; ++a) {
    const int joint = motor_hinge(m, model_name, a);
    qpos_.push_back(m->jnt_qposadr[joint]);
    qvel_.push_back(m->jnt_dofadr[joint]);
    const bool limited = m->actuator_ctrllimited[a];
    low_.push_back(limited ? m->actuator_ctrlrange[2 * a] : -1.0);
    high_.push_back(limited ? m->actuator_ctrlrange[2 * a + 1] : 1.0);
    if (pitch >= 0 && m->body_parentid[m->jnt_bodyid[joint]] == root && about_y(m, joint)) balance_.push_back(a);
  }
  for (const auto& s : styles_)
    if (static_cast<int>(s.amplitude.size()) != m->nu || static_cast<int>(s.offset.size()) != m->nu ||
        static_cast<int>(s.phase.size()) != m->nu)
      throw std::invalid_argument(model_name + ": gait style '" + s.name + "' needs one amplitude, offset and phase "
                                  "per actuator (" + std::to_string(m->nu) + ")");
}

void ScriptedGait::control(int style, double time, const double* qpos, const double* qvel, double* ctrl) const {
  const GaitStyle& s = styles_.at(style);
  const double angle = 2 * M_PI * s.frequency * time;
  for (size_t a = 0; a < qpos_.size(); ++a) {
    const double target = s.offset[a] + s.amplitude[a] * std::sin(angle + s.phase[a]);
    ctrl[a] = s.kp * (target - qpos[qpos_[a]]) - s.kd * qvel[qvel_[a]];
  }
  for (int a : balance_) ctrl[a] += s.pitch_kp * (qpos[pitch_qpos_] - s.lean) + s.pitch_kd * qvel[pitch_qvel_];
  for (size_t a = 0; a < qpos_.size(); ++a) ctrl[a] = std::clamp(ctrl[a], low_[a], high_[a]);
}

std::vector<GaitStyle> gait_styles(const mjModel* m, const std::string& model_name, int count, std::uint64_t seed,
                                   const GaitKnobs& knobs) {
  if (count < 1) throw std::invalid_argument("--styles must be at least 1, not " + std::to_string(count));
  std::vector<GaitStyle> styles;
  for (int i = 0; i < m->nnumeric; ++i)
    if (starts_with(mj_id2name(m, mjOBJ_NUMERIC, i), kStylePrefix))
      styles.push_back(style_from_custom(m, model_name, i));
  if (styles.empty()) {
    for (int k = 0; k < count; ++k) styles.push_back(drawn_style(m, model_name, knobs, seed, k));
    return styles;
  }
  if (static_cast<int>(styles.size()) < count)
    throw std::invalid_argument(model_name + " defines " + std::to_string(styles.size()) + " gait styles (" +
                                kStylePrefix + "*), fewer than the " + std::to_string(count) + " asked for");
  styles.resize(count);
  return styles;
}

BatchPolicy scripted_gait_policy(std::shared_ptr<const ScriptedGait> gait, const MujocoEnv& env,
                                 std::vector<int> style_of_episode) {
  const int nq = env.model()->nq, nv = env.model()->nv;
  const auto& names = env.observation_spec().names;
  if (env.obs_dim() != nq + nv || !starts_with(names.front(), "qpos:") || !starts_with(names[nq], "qvel:"))
    throw std::invalid_argument(env.id() + ": the scripted gait reads qpos and qvel, and this task observes "
                                "something else (it needs an MJCF body's generic task)");
  const int nu = env.act_dim();
  const double dt = env.control_timestep();
  return [gait, style_of_episode, nq, nv, nu, dt](int n, const float* observations, const int* episodes,
                                                  const int* steps, float* actions) {
    std::vector<double> qpos(nq), qvel(nv), ctrl(nu);
    for (int b = 0; b < n; ++b) {
      const float* obs = observations + static_cast<size_t>(b) * (nq + nv);
      std::copy(obs, obs + nq, qpos.begin());
      std::copy(obs + nq, obs + nq + nv, qvel.begin());
      gait->control(style_of_episode.at(episodes[b]), steps[b] * dt, qpos.data(), qvel.data(), ctrl.data());
      std::copy(ctrl.begin(), ctrl.end(), actions + static_cast<size_t>(b) * nu);
    }
  };
}

}  // namespace vaegail
