#include "experts/gait_demos.h"

#include <filesystem>
#include <memory>
#include <mutex>

#include "data/record.h"
#include "env/humanoid.h"
#include "experts/gait_controller.h"
#include "experts/gait_episode.h"
#include "util/json_file.h"
#include "util/progress.h"
#include "util/rng.h"
#include "util/thread_pool.h"

namespace vaegail {

namespace {
// A gait controller with its skeleton, which the controller only refers to.
class OwningGaitController : public PhysicsStepController {
 public:
  OwningGaitController(const mjModel* model, const GaitParameters& parameters)
      : skeleton_(model, "humanoid"), gait_(skeleton_, parameters) {}
  void control(const mjModel* model, mjData* data) override { gait_.control(model, data); }

 private:
  GaitSkeleton skeleton_;
  GaitController gait_;
};
}  // namespace

GaitDemonstrator read_gait_demonstrator(const std::string& path) {
  const nlohmann::json style = read_json_file(path);
  const std::filesystem::path p(path);
  const std::string set = style.value("set", p.parent_path().filename().string());
  return {set + "/" + style.value("style", p.stem().string()), read_gait_style(path)};
}

std::vector<Episode> record_gait_demos(const std::vector<GaitDemonstrator>& styles, const GaitDemoOptions& options,
                                       DemoHeader* header, Progress* progress) {
  if (styles.empty()) throw std::invalid_argument("no gait styles to demonstrate");
  if (header) *header = header_for(HumanoidEnv());
  std::vector<Episode> episodes(options.episodes);
  std::mutex progress_mutex;
  ThreadPool pool(options.threads);
  pool.parallel_for(options.episodes, [&](int i) {
    thread_local std::unique_ptr<HumanoidEnv> env;  // one per thread: episodes run side by side
    if (!env) env = std::make_unique<HumanoidEnv>();
    const int k = i % static_cast<int>(styles.size());
    Episode& e = episodes[i];
    e.seed = derive_seed(options.seed, static_cast<std::uint64_t>(i));
    e.context = {static_cast<double>(k)};
    e.expert_id = styles[k].label;
    const int n_obs = env->obs_dim(), n_act = env->act_dim(), n_features = static_cast<int>(env->feature_names().size());
    const auto record_state = [&](const HumanoidEnv& at) {
      e.observations.resize(e.observations.size() + n_obs);
      at.observe(e.observations.data() + e.observations.size() - n_obs);
      e.features.resize(e.features.size() + n_features);
      at.features(e.features.data() + e.features.size() - n_features);
    };
    GaitEpisodeOptions episode;
    episode.seed = e.seed;
    episode.action_noise = options.action_noise;
    if (options.learner_for) episode.learner = options.learner_for(i, k);
    episode.learner_share = options.learner_share;
    run_gait_episode(*env, styles[k].parameters, episode,
                     [&](const HumanoidEnv& at, const float* mean_action, const StepOutcome* outcome) {
                       if (outcome) {  // after a control step (else: the reset)
                         e.actions.insert(e.actions.end(), mean_action, mean_action + n_act);
                         e.rewards.push_back(outcome->reward);
                         e.terminations.push_back(outcome->terminated);
                         e.truncations.push_back(outcome->truncated);
                       }
                       record_state(at);
                     });
    for (int f = 0; f < n_features; ++f) e.attributes["mean_" + env->feature_names()[f]] = e.mean_feature(f, n_features);
    if (progress) {
      std::lock_guard<std::mutex> lock(progress_mutex);
      progress->advance();
    }
  });
  return episodes;
}

std::unique_ptr<PhysicsStepController> make_gait_demonstrator(const mjModel* model, const GaitParameters& parameters) {
  return std::make_unique<OwningGaitController>(model, parameters);
}

}  // namespace vaegail
