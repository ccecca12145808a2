#include "eval/transitions.h"

#include <algorithm>
#include <cstdlib>
#include <fmt/format.h>
#include <iterator>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <stdexcept>

#include "experts/humanoid_gait.h"
#include "util/rng.h"
#include "vae/demo_dataset.h"

namespace vaegail::eval {

double BlendSchedule::alpha(int step) const {
  if (step < start) return 0.0;
  if (step >= end()) return 1.0;
  return static_cast<double>(step - start + 1) / width;
}

BlendSchedule mid_episode_blend(int episode_length, int width) {
  if (width < 1) throw std::invalid_argument("blend: the width must be at least 1 control step, not " +
                                             std::to_string(width));
  return {episode_length / 2, width};
}

torch::Tensor blended_latents(const torch::Tensor& z_from, const torch::Tensor& z_to, const torch::Tensor& rows,
                              const torch::Tensor& steps, const BlendSchedule& blend) {
  std::vector<float> alphas;
  const auto* s = steps.data_ptr<int64_t>();
  for (int64_t i = 0; i < steps.numel(); ++i) alphas.push_back(static_cast<float>(blend.alpha(static_cast<int>(s[i]))));
  const auto alpha = torch::tensor(alphas).unsqueeze(1);
  const auto a = z_from.index_select(0, rows), b = z_to.index_select(0, rows);
  return torch::where(alpha >= 1.0f, b, a + alpha * (b - a));
}

namespace {

int feature_index(const std::vector<std::string>& names, const std::string& name, const std::string& owner) {
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end()) throw std::invalid_argument(owner + ": no feature '" + name + "'");
  return static_cast<int>(it - names.begin());
}

std::string number_label(double v) { return fmt::format("{:g}", v); }

}  // namespace

BehaviourJudge walker_speed_judge(const std::vector<std::string>& feature_names, double tolerance) {
  const int speed = feature_index(feature_names, "com_speed", "walker speed judge");
  const int n_features = static_cast<int>(feature_names.size());
  BehaviourJudge judge;
  judge.noun = "speed";
  judge.rule = fmt::format("the mean forward speed is within {:.2f} m/s of B's demonstration's", tolerance);
  judge.speed_feature = "com_speed";
  judge.of_demonstration = [](const DemoSet& demos, int64_t episode) {
    const Episode& e = demos.episodes.at(episode);
    return Behaviour{e.context.empty() ? "" : number_label(e.context[0]), vae::achieved_speed(demos, episode)};
  };
  judge.of_rollout = [speed, n_features](const Episode& rollout, int from_step) {
    double sum = 0;
    int n = 0;
    for (int t = from_step + 1; t <= rollout.length(); ++t, ++n)
      sum += rollout.features[static_cast<size_t>(t) * n_features + speed];
    return Behaviour{"", n ? sum / n : std::nan("")};
  };
  judge.matches = [tolerance](const Behaviour& rollout, const Behaviour& demonstration) {
    return std::abs(rollout.speed - demonstration.speed) <= tolerance;  // false for NaN
  };
  return judge;
}

BehaviourJudge humanoid_style_judge(const DemoSet& demos, const std::vector<std::string>& feature_names, double dt) {
  // What the classifiers are fitted on, copied so that the judge needs no caller's DemoSet to
  // live on: the demonstrations' features and styles (a few MB), not their observations.
  auto styles = std::make_shared<DemoSet>();
  styles->path = demos.path;
  styles->header.feature_names = demos.header.feature_names;
  for (const Episode& e : demos.episodes) {
    Episode slim;
    slim.features = e.features;
    slim.rewards = e.rewards;
    slim.expert_id = e.expert_id;
    styles->episodes.push_back(std::move(slim));
  }
  // One classifier per stretch asked about (the blend's end plus the settling: one in practice);
  // the whole episodes' fitted now, so that a file that cannot be classified fails here.
  struct Fitted {
    std::mutex mutex;
    std::map<int, StyleClassifier> by_from;
  };
  auto fitted = std::make_shared<Fitted>();
  fitted->by_from.emplace(0, StyleClassifier(*styles, dt));
  BehaviourJudge judge;
  judge.noun = "style";
  judge.rule = "the nearest-centroid gait classifier, fitted on the demonstrations' same stretch, names B's style";
  judge.speed_feature = "forward_speed";
  judge.of_demonstration = [dt](const DemoSet& file, int64_t episode) {
    const Episode& e = file.episodes.at(episode);
    return Behaviour{e.expert_id, gait_signature(e, file.header.feature_names, dt)[0]};
  };
  judge.of_rollout = [styles, fitted, feature_names, dt](const Episode& rollout, int from_step) {
    if (rollout.length() <= from_step) return Behaviour{"", std::nan("")};
    const GaitSignature signature = gait_signature(rollout, feature_names, dt, from_step);
    std::lock_guard<std::mutex> lock(fitted->mutex);
    auto it = fitted->by_from.find(from_step);
    if (it == fitted->by_from.end()) it = fitted->by_from.emplace(from_step, StyleClassifier(*styles, dt, from_step)).first;
    return Behaviour{it->second.name(signature), signature[0]};
  };
  judge.matches = [](const Behaviour& rollout, const Behaviour& demonstration) {
    return !rollout.label.empty() && rollout.label == demonstration.label;
  };
  return judge;
}

BehaviourJudge behaviour_judge(const Env& env, const DemoSet& demos, double speed_tolerance) {
  if (env.id() == "walker") return walker_speed_judge(env.feature_names(), speed_tolerance);
  if (env.id() == "humanoid") return humanoid_style_judge(demos, env.feature_names(), env.control_timestep());
  throw std::invalid_argument(demos.path + ": task '" + env.id() + "' has no behaviour judge for transitions "
                              "(eval/transitions.h: behaviour_judge)");
}

std::vector<TransitionPair> all_ordered_pairs(const std::vector<int64_t>& episodes) {
  std::vector<TransitionPair> pairs;
  for (const int64_t a : episodes)
    for (const int64_t b : episodes)
      if (a != b) pairs.push_back({a, b});
  return pairs;
}

std::vector<TransitionPair> sample_pairs(const std::vector<int64_t>& episodes, const std::vector<std::string>& labels,
                                         int count, std::uint64_t seed) {
  if (labels.size() != episodes.size()) throw std::invalid_argument("sample_pairs: one label per episode expected");
  std::vector<TransitionPair> candidates;
  for (size_t i = 0; i < episodes.size(); ++i)
    for (size_t j = 0; j < episodes.size(); ++j)
      if (labels[i] != labels[j]) candidates.push_back({episodes[i], episodes[j]});
  // A partial Fisher-Yates shuffle: the first `count` places are a uniform sample without replacement.
  Rng rng(seed);
  const size_t n = candidates.size(), k = std::min(n, static_cast<size_t>(std::max(count, 0)));
  for (size_t i = 0; i < k; ++i) std::swap(candidates[i], candidates[i + rng.next() % (n - i)]);
  candidates.resize(k);
  return candidates;
}

std::vector<TransitionPair> with_references(std::vector<TransitionPair> pairs) {
  const size_t n = pairs.size();
  for (size_t i = 0; i < n; ++i) {
    const TransitionPair reference{pairs[i].to, pairs[i].to};
    if (std::find(pairs.begin(), pairs.end(), reference) == pairs.end()) pairs.push_back(reference);
  }
  return pairs;
}

std::vector<vae::ImitationOutcome> roll_out_transitions(const Env& prototype, const DemoSet& demos,
                                                        const std::vector<TransitionPair>& pairs,
                                                        const torch::Tensor& z_from, const torch::Tensor& z_to,
                                                        const vae::LatentPolicy& policy, const BlendSchedule& blend,
                                                        const vae::ImitationOptions& options, Progress* progress) {
  const int64_t P = static_cast<int64_t>(pairs.size());
  if (z_from.dim() != 2 || z_from.size(0) != P || !z_to.sizes().equals(z_from.sizes()))
    throw std::invalid_argument("roll_out_transitions: z_from and z_to must both be [" + std::to_string(P) + ", Z]");
  std::vector<int64_t> starts_of;
  for (const auto& p : pairs) starts_of.push_back(p.from);
  const auto from = z_from.detach().to(torch::kCPU, torch::kFloat).contiguous();
  const auto to = z_to.detach().to(torch::kCPU, torch::kFloat).contiguous();
  const vae::LatentSchedule schedule = [&](const torch::Tensor& rows, const torch::Tensor& steps) {
    return blended_latents(from, to, rows, steps, blend);
  };
  return vae::roll_out_latent_policy(prototype, vae::rollout_starts(demos, starts_of), schedule, policy, options,
                                     progress);
}

std::vector<TransitionRow> run_transitions(const Env& prototype, const DemoSet& demos,
                                           const std::vector<TransitionPair>& pairs, const torch::Tensor& z_from,
                                           const torch::Tensor& z_to, const std::vector<NamedPolicy>& policies,
                                           const BehaviourJudge& judge, const TransitionOptions& options,
                                           Progress* progress) {
  const auto blend = mid_episode_blend(prototype.episode_length(), options.blend_width);
  const int measured_from = blend.end() + options.settle;
  if (options.settle < 0 || measured_from >= prototype.episode_length())
    throw std::invalid_argument("transitions: the blend (" + std::to_string(blend.start) + " + " +
                                std::to_string(blend.width) + " steps) and the settling (" +
                                std::to_string(options.settle) + " steps) leave nothing of the " +
                                std::to_string(prototype.episode_length()) + "-step episode to measure");
  std::vector<TransitionRow> rows;
  for (const auto& p : policies) {
    const auto outcomes =
        roll_out_transitions(prototype, demos, pairs, z_from, z_to, p.policy, blend, options.rollout, progress);
    for (size_t i = 0; i < pairs.size(); ++i) {
      TransitionRow r;
      r.policy = p.name;
      r.pair = pairs[i];
      r.from_expert = demos.episodes.at(pairs[i].from).expert_id;
      r.to_expert = demos.episodes.at(pairs[i].to).expert_id;
      r.from = judge.of_demonstration(demos, pairs[i].from);
      r.to = judge.of_demonstration(demos, pairs[i].to);
      r.fell = outcomes[i].fell;
      r.fall_step = outcomes[i].fall_step;
      r.up_at_blend = !r.fell || r.fall_step > blend.start;
      r.after = judge.of_rollout(outcomes[i].episode, measured_from);
      r.matched = !r.fell && judge.matches(r.after, r.to);
      rows.push_back(r);
    }
  }
  return rows;
}

std::string transitions_csv(const std::vector<TransitionRow>& rows) {
  std::string csv = "policy,from_episode,to_episode,from_expert,to_expert,from_behaviour,to_behaviour,from_speed,"
                    "to_speed,fell,fall_step,speed_after,behaviour_after,matched\n";
  for (const auto& r : rows)
    fmt::format_to(std::back_inserter(csv), "{},{},{},{},{},{},{},{:.6f},{:.6f},{},{},{:.6f},{},{}\n", r.policy, r.pair.from,
                   r.pair.to, r.from_expert, r.to_expert, r.from.label, r.to.label, r.from.speed, r.to.speed,
                   r.fell ? 1 : 0, r.fall_step, r.after.speed, r.after.label, r.matched ? 1 : 0);
  return csv;
}

namespace {

std::string kind_of(const TransitionRow& r) {
  if (r.reference()) return "none";
  return r.different() ? "different" : "same";
}

}  // namespace

std::vector<TransitionSummary> summarize_transitions(const std::vector<TransitionRow>& rows, bool by_labels) {
  std::vector<TransitionSummary> out;
  std::set<std::pair<std::string, int64_t>> matched_alone;  // (policy, B) whose reference matched
  for (const auto& r : rows)
    if (r.reference() && r.matched) matched_alone.insert({r.policy, r.pair.to});
  const auto add = [&](const TransitionSummary& key, const TransitionRow& r) {
    auto it = std::find_if(out.begin(), out.end(), [&](const TransitionSummary& s) {
      return s.policy == key.policy && s.pairs == key.pairs && s.from_label == key.from_label &&
             s.to_label == key.to_label;
    });
    if (it == out.end()) it = out.insert(out.end(), key);
    ++it->n;
    it->up_at_blend += r.up_at_blend;
    it->stayed_up += !r.fell;
    it->matched += r.matched;
    if (!r.reference() && matched_alone.count({r.policy, r.pair.to})) {
      ++it->b_alone;
      it->matched_b_alone += r.matched;
    }
  };
  std::vector<std::string> policies;
  for (const auto& r : rows)
    if (std::find(policies.begin(), policies.end(), r.policy) == policies.end()) policies.push_back(r.policy);
  for (const auto& policy : policies)
    for (const std::string kind : {"different", "same", "none"})
      for (const auto& r : rows) {
        if (r.policy != policy || kind_of(r) != kind || (by_labels && kind != "different")) continue;
        TransitionSummary key{policy, kind, "", "", 0, 0, 0, 0, 0, 0};
        if (by_labels) {
          key.from_label = r.from.label;
          key.to_label = r.to.label;
        }
        add(key, r);
      }
  if (by_labels)  // each policy's groups in label order, the policies in order of appearance
    std::stable_sort(out.begin(), out.end(), [&policies](const TransitionSummary& a, const TransitionSummary& b) {
      const auto rank = [&policies](const std::string& p) {
        return std::find(policies.begin(), policies.end(), p) - policies.begin();
      };
      if (a.policy != b.policy) return rank(a.policy) < rank(b.policy);
      // Numbers (the walker's speeds) by value, names (the humanoid's styles) alphabetically.
      const auto key = [](const std::string& s) {
        char* end = nullptr;
        const double v = std::strtod(s.c_str(), &end);
        return !s.empty() && *end == '\0' ? std::make_pair(v, std::string()) : std::make_pair(0.0, s);
      };
      return std::make_pair(key(a.from_label), key(a.to_label)) < std::make_pair(key(b.from_label), key(b.to_label));
    });
  for (auto& s : out) {
    s.up_at_blend /= s.n;
    s.stayed_up /= s.n;
    s.matched /= s.n;
  }
  return out;
}

std::string transition_table(const std::vector<TransitionSummary>& summaries, const std::string& noun) {
  const bool by_labels = std::any_of(summaries.begin(), summaries.end(),
                                     [](const TransitionSummary& s) { return !s.from_label.empty(); });
  const std::map<std::string, std::string> kinds{{"different", "A, B of different " + noun + "s"},
                                                 {"same", "A, B of the same " + noun},
                                                 {"none", "none: B from B's start (reference)"}};
  std::string table = std::string("| policy | ") + (by_labels ? "from " + noun + " | to " + noun : "transition") +
                      " | pairs | up at the blend | stayed up | matched B | matched B where B alone is |\n|---|" +
                      (by_labels ? "---:|---:|" : "---|") + "---:|---:|---:|---:|---:|\n";
  for (const auto& s : summaries) {
    const std::string what = by_labels ? s.from_label + " | " + s.to_label : kinds.at(s.pairs);
    const std::string alone = s.pairs == "none" ? "-" : fmt::format("{} of {}", s.matched_b_alone, s.b_alone);
    table += fmt::format("| {} | {} | {} | {:.1f}% | {:.1f}% | {:.1f}% | {} |\n", s.policy, what, s.n,
                         100.0 * s.up_at_blend, 100.0 * s.stayed_up, 100.0 * s.matched, alone);
  }
  return table;
}

}  // namespace vaegail::eval
