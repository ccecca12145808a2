#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <functional>
#include <mutex>
#include <numeric>
#include <set>
#include <thread>

#include "cli/commands.h"
#include "cli/task_options.h"
#include "bench/physics_bench.h"
#include "experts/arm_expert.h"
#include "experts/demo_collection.h"
#include "experts/expert_eval.h"
#include "experts/expert_trainer.h"
#include "experts/gait_demos.h"
#include "experts/gait_eval.h"
#include "experts/humanoid_gait.h"
#include "env/humanoid.h"
#include "data/demos.h"
#include "util/atomic_file.h"
#include "util/csv_log.h"
#include "util/json_file.h"
#include "util/progress.h"
#include "util/run_lock.h"
#include "vae/imitation.h"
#include "vae/policy_refit.h"
#include "vae/trained_vae.h"

namespace vaegail::cli {

namespace fs = std::filesystem;

namespace {

struct ExpertTrainFlags {
  std::string task = "walker";
  std::string out_dir = "experts/walker";
  std::string grid = "paper";
  std::string config;
  std::vector<std::string> only;
  std::int64_t steps = 0;
  int jobs = 1;
  std::string device = "cpu";
  int count = 60;              // arm: experts, each with its own random target
  std::uint64_t seed = 0;      // arm: the targets' stream
};


template <class Spec>
std::vector<Spec> selected(const std::vector<Spec>& all, const std::vector<std::string>& only) {
  std::vector<Spec> specs;
  for (const auto& s : all)
    if (only.empty() || std::find(only.begin(), only.end(), s.id) != only.end()) specs.push_back(s);
  if (specs.empty()) throw std::invalid_argument("no expert of the set matches --only");
  return specs;
}

// Trains experts `jobs` at a time (one thread each) under one progress bar. train(i, report)
// trains expert i and calls report(steps done) as it goes; done[i] holds the steps a resumed
// run already has, counted as done from the start so the rate and ETA measure only new work.
void train_in_parallel(const std::vector<std::string>& ids, std::vector<std::int64_t> done, std::int64_t steps_each,
                       int jobs, const std::function<void(size_t, const std::function<void(std::int64_t)>&)>& train) {
  Progress progress("experts", static_cast<std::int64_t>(ids.size()) * steps_each, "steps");
  progress.resume(std::accumulate(done.begin(), done.end(), std::int64_t{0}));
  std::mutex mutex;
  size_t next = 0;
  std::exception_ptr error;
  auto worker = [&] {
    for (;;) {
      size_t i;
      {
        std::lock_guard<std::mutex> lock(mutex);
        if (next >= ids.size() || error) return;
        i = next++;
      }
      try {
        train(i, [&, i](std::int64_t steps) {
          std::lock_guard<std::mutex> lock(mutex);
          done[i] = steps;
          progress.set_status(ids[i]);
          progress.set(std::accumulate(done.begin(), done.end(), std::int64_t{0}));
        });
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex);
        if (!error) error = std::current_exception();
      }
    }
  };
  std::vector<std::thread> threads;
  for (int j = 0; j < jobs; ++j) threads.emplace_back(worker);
  for (auto& t : threads) t.join();
  if (error) std::rethrow_exception(error);
  progress.finish();
}

// The config's "grid", or its "grids" one after another (the humanoid's training and evaluation
// controllers, seeded apart); the walker's --grid without either. Every grid trains on --task.
std::vector<ExpertSpec> ppo_expert_specs(const ExpertTrainFlags& f, const nlohmann::json& config) {
  std::vector<ExpertGrid> grids;
  if (config.contains("grids")) grids = config["grids"].get<std::vector<ExpertGrid>>();
  if (config.contains("grid")) grids.push_back(config["grid"].get<ExpertGrid>());
  if (grids.empty() && f.task != "walker")
    throw std::invalid_argument("experts train --task " + f.task + ": --config must give a 'grid' or 'grids'");
  if (grids.empty()) grids.push_back(f.grid == "small" ? small_walker_grid() : paper_walker_grid());
  std::vector<ExpertSpec> specs;
  for (auto& grid : grids) {
    grid.task = f.task;
    for (auto& s : expand(grid)) specs.push_back(std::move(s));
  }
  return specs;
}

void run_train_ppo(const ExpertTrainFlags& f) {
  const nlohmann::json config = f.config.empty() ? nlohmann::json::object() : read_json_file(f.config);
  ExpertTrainOptions options;
  if (config.contains("training")) options = config["training"].get<ExpertTrainOptions>();
  if (f.steps > 0) options.total_steps = f.steps;
  options.device = f.device;
  const auto specs = selected(ppo_expert_specs(f, config), f.only);
  const RunLock lock = lock_run_directory(f.out_dir);  // one for all the experts; creates the directory
  std::printf("training %zu expert(s) into %s, %lld steps each, %d at a time\n", specs.size(), f.out_dir.c_str(),
              static_cast<long long>(options.total_steps), f.jobs);
  std::vector<std::string> ids;
  std::vector<std::int64_t> done;
  for (const auto& s : specs) {
    ids.push_back(s.id);
    done.push_back(std::min(expert_steps(f.out_dir + "/" + s.id), options.total_steps));
  }
  train_in_parallel(ids, done, options.total_steps, f.jobs, [&](size_t i, const auto& report) {
    train_expert(specs[i], options, f.out_dir + "/" + specs[i].id, report);
  });
}

// One line per reaching expert: its target, the best noise-free return (of 50) and the final
// grip-to-target distance and path ratio of that episode; then the medians.
std::string arm_expert_table(const std::vector<ArmExpertSpec>& specs, const std::vector<ArmExpertResult>& results) {
  std::string out = fmt::format("{:<10} {:>28} {:>12} {:>16} {:>11}\n", "expert", "target (m)", "best return",
                                "final dist (cm)", "path ratio");
  std::vector<double> distances, ratios;
  for (size_t i = 0; i < specs.size(); ++i) {
    out += fmt::format("{:<10} ({:7.3f}, {:7.3f}, {:7.3f}) {:12.2f} {:16.1f} {:11.2f}\n", specs[i].id, specs[i].target[0],
                       specs[i].target[1], specs[i].target[2], results[i].best_return, 100 * results[i].final_distance,
                       results[i].path_ratio);
    distances.push_back(results[i].final_distance);
    ratios.push_back(results[i].path_ratio);
  }
  std::sort(distances.begin(), distances.end());
  std::sort(ratios.begin(), ratios.end());
  return out + fmt::format("{} experts, median final distance {:.1f} cm, worst {:.1f} cm; median path ratio {:.2f}\n",
                           distances.size(), 100 * distances[distances.size() / 2], 100 * distances.back(),
                           ratios[ratios.size() / 2]);
}

// The arm's experts train on the CPU whatever --device says: DDPG's one-sample steps would
// spend their time in transfers.
void run_train_arm(const ExpertTrainFlags& f) {
  ArmExpertOptions options;
  if (!f.config.empty()) {
    const auto j = read_json_file(f.config);
    if (j.contains("training")) options = j["training"].get<ArmExpertOptions>();
  }
  if (f.steps > 0) options.total_steps = f.steps;
  const auto specs = selected(arm_expert_specs(f.count, f.seed), f.only);
  const RunLock lock = lock_run_directory(f.out_dir);  // one for all the experts; creates the directory
  std::printf("training %zu reaching expert(s) into %s, %lld steps each, %d at a time\n", specs.size(),
              f.out_dir.c_str(), static_cast<long long>(options.total_steps), f.jobs);
  std::vector<std::string> ids;
  std::vector<std::int64_t> done;
  for (const auto& s : specs) {
    ids.push_back(s.id);
    done.push_back(arm_expert_done(f.out_dir + "/" + s.id) ? options.total_steps : 0);
  }
  std::vector<ArmExpertResult> results(specs.size());
  train_in_parallel(ids, done, options.total_steps, f.jobs, [&](size_t i, const auto& report) {
    results[i] = train_arm_expert(specs[i], options, f.out_dir + "/" + specs[i].id, report);
  });
  std::fputs(arm_expert_table(specs, results).c_str(), stdout);
}

void run_expert_train(const ExpertTrainFlags& f) {
  if (f.task == "arm") return run_train_arm(f);
  run_train_ppo(f);
}

std::vector<std::string> expert_dirs(const std::string& root, const std::vector<std::string>& only) {
  if (!fs::is_directory(root)) throw std::runtime_error(root + ": no such directory of experts");
  std::vector<std::string> dirs;
  for (const auto& entry : fs::directory_iterator(root)) {
    if (!fs::exists(entry.path() / "spec.json")) continue;
    const std::string id = entry.path().filename().string();
    if (only.empty() || std::find(only.begin(), only.end(), id) != only.end()) dirs.push_back(entry.path().string());
  }
  std::sort(dirs.begin(), dirs.end());
  if (dirs.empty()) throw std::runtime_error(root + ": holds no expert runs" + (only.empty() ? "" : " matching --only"));
  return dirs;
}

// Several directories: their runs in order, each id once.
std::vector<std::string> expert_dirs(const std::vector<std::string>& roots, const std::vector<std::string>& only) {
  std::vector<std::string> dirs;
  std::set<std::string> ids;
  for (const auto& root : roots)
    for (auto& dir : expert_dirs(root, only)) {
      if (!ids.insert(fs::path(dir).filename().string()).second)
        throw std::runtime_error(dir + ": expert id repeats another --experts-dir");
      dirs.push_back(std::move(dir));
    }
  return dirs;
}

struct EvalFlags {
  std::string dir = "experts/walker";
  std::vector<std::string> only;
  ExpertEvalOptions eval;
  std::string json_out;
  std::string task;                  // empty: the experts' own, from --dir
  std::vector<std::string> styles;   // humanoid gait controllers' style files
  GaitEvalOptions gait;
  std::string csv_out;
  double raw_seconds = 2.0;          // measuring time of each style's raw physics figure
};

// Arm experts keep their noise-free evaluation (the start and the actor are deterministic).
void run_eval_arm(const std::vector<std::string>& dirs, const std::string& json_out) {
  std::vector<ArmExpertSpec> specs;
  std::vector<ArmExpertResult> results;
  nlohmann::json report = nlohmann::json::array();
  for (const auto& d : dirs) {
    const LoadedArmExpert e = load_arm_expert(d);
    specs.push_back(e.spec);
    results.push_back(e.result);
    report.push_back({{"id", e.spec.id}, {"target", e.spec.target}, {"best_return", e.result.best_return},
                      {"final_distance", e.result.final_distance}, {"path_ratio", e.result.path_ratio}});
  }
  std::fputs(arm_expert_table(specs, results).c_str(), stdout);
  if (!json_out.empty()) write_file_atomically(json_out, report.dump(2));
}

// The gait controllers of style files, each over the same starts and followed by the raw physics
// figure of the same model, so that the two rates compare under the same load.
void run_gait_eval(const EvalFlags& f) {
  if (!f.task.empty() && f.task != "humanoid")
    throw std::invalid_argument("experts eval --styles: gait controllers drive the humanoid, not --task " + f.task);
  std::vector<GaitDemonstrator> styles;
  for (const auto& path : f.styles) styles.push_back(read_gait_demonstrator(path));
  Progress progress("eval", static_cast<std::int64_t>(styles.size()) * f.gait.episodes, "starts");
  std::vector<GaitStyleEvaluation> results;
  const HumanoidEnv env;
  for (const auto& style : styles) {
    progress.set_status(style.label);
    results.push_back(evaluate_gait_style(style.label, style.parameters, f.gait, [&] { progress.advance(); }));
    if (f.raw_seconds > 0)
      results.back().raw_control_steps_per_s =
          raw_physics_steps_per_s(env, f.raw_seconds) * env.model()->opt.timestep / env.control_timestep();
  }
  progress.finish();
  std::fputs(format_gait_evaluations(results).c_str(), stdout);
  if (!f.csv_out.empty()) {
    std::string csv = "style";
    for (const auto& [column, value] : gait_evaluation_row(results.front())) csv += "," + column;
    csv += ",raw_control_steps_per_s\n";
    for (const auto& e : results) {
      csv += e.name;
      for (const auto& [column, value] : gait_evaluation_row(e)) csv += fmt::format(",{}", value);
      csv += fmt::format(",{}\n", e.raw_control_steps_per_s);
    }
    write_file_atomically(f.csv_out, csv);
  }
  if (!f.json_out.empty()) {
    nlohmann::json report = nlohmann::json::array();
    for (const auto& e : results) {
      nlohmann::json row = {{"style", e.name}, {"parameters", e.parameters}, {"raw_control_steps_per_s", e.raw_control_steps_per_s}};
      for (const auto& [column, value] : gait_evaluation_row(e)) row[column] = value;
      report.push_back(row);
    }
    write_file_atomically(f.json_out, report.dump(2));
  }
}

void run_eval(const EvalFlags& f) {
  if (!f.styles.empty()) return run_gait_eval(f);
  const auto dirs = expert_dirs(f.dir, f.only);
  if (fs::exists(fs::path(dirs.front()) / "actor.pt")) return run_eval_arm(dirs, f.json_out);
  std::vector<ExpertEvaluation> results;
  Progress progress("eval", static_cast<std::int64_t>(dirs.size()), "experts");
  nlohmann::json report = nlohmann::json::array();
  for (const auto& d : dirs) {
    results.push_back(evaluate_expert(load_expert(d), f.eval));
    nlohmann::json targets = nlohmann::json::array();
    for (const auto& t : results.back().targets)
      targets.push_back({{"target", t.target}, {"label", t.label}, {"target_speed", t.target_speed},
                         {"episodes", t.episodes}, {"mean_speed", t.mean_speed}, {"speed_error", t.speed_error},
                         {"fall_rate", t.fall_rate}});
    report.push_back({{"id", results.back().id}, {"passes", results.back().passes()}, {"targets", targets}});
    progress.advance();
  }
  progress.finish();
  std::fputs(format_evaluations(results).c_str(), stdout);
  if (!f.json_out.empty()) write_file_atomically(f.json_out, report.dump(2));
}

struct CollectFlags {
  std::string task = "walker";
  std::vector<std::string> dirs = {"experts/walker"};
  int episodes = 0;  // 0: the task's paper value (walker 20, arm 30)
  double noise = ArmCollectOptions{}.noise_std;
  double offset = 0;
  std::vector<std::string> only;
  std::string out;
  std::vector<std::string> held_out;
  std::vector<std::string> passing;
  CollectOptions collect;
  bool force = false;
  std::vector<std::string> styles;  // humanoid: gait controllers' style files
  double action_noise = 0;          // with them: DART's execution noise
  std::string learner;              // and DAgger's learner: a VAE run whose policy acts on a share of steps
  double learner_share = 0.5;
  std::string z_from;               // the demonstrations whose mu give the learner each style's z
};

// DAgger's learner: the VAE policy's mean action, held over the step as in every imitation; in
// episode i of style k its z is the mu of a random demonstration in `z_from` by the same
// demonstrator (matched by expert id, not by context index, so that the two files may list the
// styles in another order), as `vae refit-policy --z-from` lends it.
std::function<std::function<void(const float*, float*)>(int, int)> vae_learner(
    const std::string& run, const std::string& z_from, const std::vector<GaitDemonstrator>& styles, int episodes,
    std::uint64_t seed) {
  auto model = vae::load_trained_vae(run);
  model->eval();
  const DemoSet clean = read_demos(z_from);  // its dimensions are checked against the VAE's by the encoding below
  std::vector<int64_t> source;
  std::vector<double> source_styles;
  for (size_t j = 0; j < clean.episodes.size(); ++j)
    for (size_t k = 0; k < styles.size(); ++k)
      if (clean.episodes[j].expert_id == styles[k].label) {
        source.push_back(static_cast<int64_t>(j));
        source_styles.push_back(static_cast<double>(k));
      }
  for (size_t k = 0; k < styles.size(); ++k)
    if (std::find(source_styles.begin(), source_styles.end(), static_cast<double>(k)) == source_styles.end())
      throw std::invalid_argument(z_from + ": no demonstration by " + styles[k].label + " to lend the learner its z");
  std::vector<double> episode_styles(episodes);
  for (int i = 0; i < episodes; ++i) episode_styles[i] = i % static_cast<int>(styles.size());
  Progress progress("encode", static_cast<std::int64_t>(source.size()), "demos");
  const torch::Tensor mu = vae::encode_episodes(model, clean, source, nullptr, &progress);
  progress.finish();
  const torch::Tensor z = vae::latents_by_label(mu, source_styles, episode_styles, seed);
  return [model, z](int episode, int) -> std::function<void(const float*, float*)> {
    const torch::Tensor row = z[episode].unsqueeze(0);
    return [model, row](const float* observation, float* action) mutable {
      torch::NoGradGuard no_grad;
      const int64_t state_dim = model->config().state_dim;
      const auto x = torch::from_blob(const_cast<float*>(observation), {1, state_dim}, torch::kFloat32);
      const auto a = model->action_mean(x, row).to(torch::kFloat32).contiguous();
      std::copy_n(a.data_ptr<float>(), a.numel(), action);
    };
  };
}

// The humanoid's gait controllers: --episodes in all (default 250), episode i in style i mod K.
void collect_gait_demos(const CollectFlags& f) {
  std::vector<GaitDemonstrator> styles;
  for (const auto& path : f.styles) styles.push_back(read_gait_demonstrator(path));
  GaitDemoOptions o;
  o.episodes = f.episodes > 0 ? f.episodes : o.episodes;
  o.seed = f.collect.seed;
  o.threads = f.collect.threads;
  o.action_noise = f.action_noise;
  if (!f.learner.empty()) {
    o.learner_for = vae_learner(f.learner, f.z_from, styles, o.episodes, o.seed);
    o.learner_share = f.learner_share;
  }
  DemoHeader header;
  Progress progress("collect", o.episodes, "episodes");
  const std::vector<Episode> episodes = record_gait_demos(styles, o, &header, &progress);
  DemoWriter writer(f.out, header);
  for (const auto& e : episodes) writer.append(e);
  writer.commit();
  progress.finish();
  std::printf("wrote %s: %zu gait styles, %d episodes%s%s\n", f.out.c_str(), styles.size(), o.episodes,
              o.action_noise > 0 ? fmt::format(" (execution noise {}, clean labels)", o.action_noise).c_str() : "",
              o.learner_for ? fmt::format(" (DAgger: the learner acts on {} of the steps, clean labels)", o.learner_share).c_str() : "");
}

void run_collect(CollectFlags f) {
  const RunLock lock = lock_output_file(f.out);
  if (fs::exists(f.out) && !f.force) throw std::runtime_error(f.out + ": exists (pass --force to replace it)");
  if (f.action_noise > 0 && f.styles.empty())
    throw std::invalid_argument("--action-noise is for the humanoid's gait controllers (--styles)");
  if (!f.learner.empty() && f.styles.empty())
    throw std::invalid_argument("--learner is for the humanoid's gait controllers (--styles)");
  if (f.learner.empty() != f.z_from.empty()) throw std::invalid_argument("--learner and --z-from go together");
  if (!f.styles.empty()) {
    if (f.task != "humanoid") throw std::invalid_argument("--styles is for --task humanoid (gait controllers)");
    if (fs::path(f.out).has_parent_path()) fs::create_directories(fs::path(f.out).parent_path());
    return collect_gait_demos(f);
  }
  std::vector<std::string> passing;
  for (const auto& path : f.passing) {  // experts that passed the bar in `experts eval --json` reports
    const auto report = nlohmann::json::parse(read_file(path));
    const auto before = passing.size();
    for (const auto& e : report)
      if (e.at("passes").get<bool>()) passing.push_back(e.at("id"));
    if (passing.size() == before) throw std::runtime_error(path + ": no expert passes the bar");
  }
  // Both flags narrow the set: with both, an expert must be named by --only and pass.
  std::vector<std::string> only = f.only.empty() ? passing : f.only;
  if (!f.only.empty() && !f.passing.empty()) {
    const auto fails = [&](const std::string& id) { return std::find(passing.begin(), passing.end(), id) == passing.end(); };
    only.erase(std::remove_if(only.begin(), only.end(), fails), only.end());
    if (only.empty()) throw std::invalid_argument("no expert named by --only passes in the --passing reports");
  }
  const auto dirs = expert_dirs(f.dirs, only);
  for (const auto& id : f.held_out)
    if (std::none_of(dirs.begin(), dirs.end(), [&](const std::string& d) { return fs::path(d).filename() == id; }))
      throw std::invalid_argument("--held-out " + id + ": no such expert in --experts-dir");
  if (fs::path(f.out).has_parent_path()) fs::create_directories(fs::path(f.out).parent_path());
  int episodes = f.episodes;
  if (f.task == "arm") {
    ArmCollectOptions o;
    if (episodes > 0) o.episodes_per_expert = episodes;
    episodes = o.episodes_per_expert;
    o.noise_std = f.noise;
    o.offset_std = f.offset;
    o.seed = f.collect.seed;
    o.held_out = f.held_out;
    Progress progress("collect", static_cast<std::int64_t>(dirs.size()) * episodes, "episodes");
    collect_arm_demos(dirs, f.out, o, &progress);
    progress.finish();
  } else {
    if (episodes > 0) f.collect.episodes_per_expert = episodes;
    episodes = f.collect.episodes_per_expert;
    f.collect.held_out.insert(f.held_out.begin(), f.held_out.end());
    Progress progress("collect", static_cast<std::int64_t>(dirs.size()) * episodes, "episodes");
    collect_demos(dirs, f.out, f.collect, &progress);
    progress.finish();
  }
  std::printf("wrote %s: %zu experts x %d episodes\n", f.out.c_str(), dirs.size(), episodes);
}

// The style classifier of the bar: gait signatures of a humanoid demonstration file,
// fitted on half of each style's episodes, naming the other half; prints the confusion table.
void run_styles(const std::string& path) {
  const DemoSet demos = read_demos(path);
  const auto env = demo_env(demos);
  const auto* humanoid = dynamic_cast<const HumanoidEnv*>(env.get());
  if (!humanoid) throw std::invalid_argument(path + ": demos styles reads humanoid demonstrations, not " + env->id());
  std::vector<GaitSignature> rows;
  for (const auto& e : demos.episodes)
    rows.push_back(gait_signature(e, demos.header.feature_names, env->control_timestep()));
  const auto [names, labels] = style_labels(demos);
  const Confusion confusion = split_half_confusion(rows, labels);
  // A Markdown table (docs/ quotes it): a row per true style, a column per style named.
  std::printf("| true \\ named |");
  for (const auto& [style, row] : confusion) std::printf(" %s |", names.at(style).c_str());
  std::printf("\n| --- |");
  for (size_t k = 0; k < confusion.size(); ++k) std::printf(" ---: |");
  std::printf("\n");
  int named_episodes = 0;
  for (const auto& [style, row] : confusion) {
    std::printf("| %s |", names.at(style).c_str());
    for (const auto& [named, unused] : confusion) {
      const auto count = row.find(named);
      std::printf(" %d |", count == row.end() ? 0 : count->second);
      named_episodes += count == row.end() ? 0 : count->second;
    }
    std::printf("\n");
  }
  std::printf("%.1f%% of %d held-out episodes named right (nearest centroid on %zu gait statistics)\n",
              100 * accuracy(confusion), named_episodes, kGaitStatistics.size());
}

}  // namespace

void add_expert_commands(CLI::App& app) {
  CLI::App* experts = app.add_subcommand("experts", "train and evaluate the RL experts that demonstrate");
  experts->require_subcommand(1);

  auto t = std::make_shared<ExpertTrainFlags>();
  CLI::App* train = experts->add_subcommand("train", "train target-speed experts with PPO (resumable)");
  train->add_option("--task", t->task, "walker (PPO, target speeds), humanoid (PPO on its style-free reward, a --config grid of style labels) or arm (DDPG, random reach targets)")
      ->check(CLI::IsMember({"walker", "humanoid", "arm"}))->capture_default_str();
  train->add_option("--out-dir", t->out_dir, "one run directory per expert goes here")->capture_default_str();
  train->add_option("--grid", t->grid, "paper: 72 experts (6 speed groups x 4 log-std x 3 seeds); small: 12")
      ->check(CLI::IsMember({"paper", "small"}))->capture_default_str();
  train->add_option("--config", t->config, "JSON with optional 'grid' or 'grids' (PPO tasks) and 'training' objects (e.g. configs/walker_experts_published.json)")
      ->check(CLI::ExistingFile);
  train->add_option("--only", t->only, "train only these expert ids");
  train->add_option("--steps", t->steps, "environment steps per expert (overrides the config)")->check(CLI::Range(int64_t{1}, int64_t{1} << 40));
  train->add_option("--count", t->count, "arm: number of experts (the paper: 60)")->check(CLI::Range(1, 10000))->capture_default_str();
  train->add_option("--seed", t->seed, "arm: seed of the targets and of training")->capture_default_str();
  train->add_option("--jobs", t->jobs, "experts trained at once (one core each)")->check(CLI::Range(1, 64))->capture_default_str();
  add_device_option(*train, t->device);
  train->callback([t] { run_expert_train(*t); });

  auto e = std::make_shared<EvalFlags>();
  CLI::App* eval = experts->add_subcommand("eval", "walker: mean speed, distance to target and fall rate per expert and target; arm: final distance to the target; humanoid --styles: gait controllers' falls with and without pushes, gait measures and speed");
  eval->add_option("--dir", e->dir, "directory of expert runs")->capture_default_str();
  eval->add_option("--only", e->only, "evaluate only these expert ids");
  eval->add_option("--episodes", e->eval.episodes_per_target, "episodes per target speed")->check(CLI::Range(1, 100000))->capture_default_str();
  eval->add_flag("--stochastic", e->eval.stochastic, "sample actions instead of taking the mean");
  eval->add_option("--seed", e->eval.seed, "episode seeds")->capture_default_str();
  eval->add_option("--json", e->json_out, "also write the table as JSON (input of demos collect --passing)");
  eval->add_option("--task", e->task, "the experts' task (default: --dir's own); humanoid with --styles")
      ->check(CLI::IsMember({"walker", "humanoid", "arm"}));
  eval->add_option("--styles", e->styles, "humanoid gait controllers' style files (configs/humanoid_styles/*/*.json): evaluate these instead of --dir; --episodes defaults to 20 starts, each walked without and with pushes")
      ->check(CLI::ExistingFile);
  eval->add_option("--pushes", e->gait.episode.pushes, "--styles: pushes on the pelvis per pushed episode, at uniform times in [2, 8] s and directions")
      ->check(CLI::Range(0, 100))->capture_default_str();
  eval->add_option("--push-force", e->gait.episode.push_force, "--styles: each push's force (N)")->check(CLI::Range(0.0, 1e4))->capture_default_str();
  eval->add_option("--push-duration", e->gait.episode.push_duration, "--styles: each push's duration (s)")->check(CLI::Range(0.0, 10.0))->capture_default_str();
  eval->add_flag("--replay", e->gait.replay, "--styles: also the held-mean replay figure per start (control steps until the root is 0.1 m off when the recorded mean actions are replayed held)");
  eval->add_option("--csv", e->csv_out, "--styles: also write one row per style here");
  eval->add_option("--raw-seconds", e->raw_seconds, "--styles: seconds of bare mj_step measured after each style's episodes, for its raw physics figure (0: skip)")
      ->check(CLI::Range(0.0, 600.0))->capture_default_str();
  eval->callback([e, eval] {
    if (!e->styles.empty()) {
      e->gait.episodes = eval->count("--episodes") ? e->eval.episodes_per_target : 20;
      e->gait.seed = e->eval.seed;
    }
    run_eval(*e);
  });

  add_experts_tune(*experts);


  auto c = std::make_shared<CollectFlags>();
  CLI::App* demos = app.add_subcommand("demos", "demonstration sets from experts");
  demos->require_subcommand(1);
  CLI::App* collect = demos->add_subcommand("collect", "roll experts out into an HDF5 demonstration file");
  collect->add_option("--task", c->task, "walker, humanoid (PPO experts: their own task) or arm (the experts' kind)")
      ->check(CLI::IsMember({"walker", "humanoid", "arm"}))->capture_default_str();
  collect->add_option("--experts-dir", c->dirs, "directories of expert runs (expert ids must not repeat across them)")->capture_default_str();
  collect->add_option("--only", c->only, "collect only from these expert ids");
  collect->add_option("--passing", c->passing, "collect only from experts that pass in these `experts eval --json` reports")
      ->check(CLI::ExistingFile);
  collect->add_option("--out", c->out, "output .h5 file")->required();
  collect->add_option("--episodes-per-expert", c->episodes, "episodes per expert (default: walker 20, arm 30, as the paper)")
      ->check(CLI::Range(1, 100000));
  collect->add_flag("--stochastic", c->collect.stochastic, "walker: sample actions (default: mean actions)");
  collect->add_option("--noise", c->noise, "arm: std (rad) of the Gaussian noise on the executed joint commands (the demonstration records the expert's own)")
      ->check(CLI::Range(0.0, 1.0))->capture_default_str();
  collect->add_option("--offset", c->offset, "arm: std (rad) of a per-episode constant offset on every joint command, recorded in the demonstration (0: none)")
      ->check(CLI::Range(0.0, 1.0))->capture_default_str();
  collect->add_option("--held-out", c->held_out, "expert ids marked held_out = 1 (kept out of VAE training)");
  collect->add_option("--seed", c->collect.seed, "episode seeds")->capture_default_str();
  collect->add_option("--styles", c->styles, "humanoid: gait controllers' style files (configs/humanoid_styles/*/*.json) instead of --experts-dir; --episodes-per-expert is then the episodes in all (default 250), episode i in style i mod K")
      ->check(CLI::ExistingFile);
  collect->add_option("--action-noise", c->action_noise, "humanoid --styles: std of Gaussian noise on every motor command, one draw per control step, while each step records the clean controller's mean command from its start state (DART; 0: clean demonstrations)")
      ->check(CLI::Range(0.0, 1.0))->capture_default_str();
  collect->add_option("--learner", c->learner, "humanoid --styles: DAgger's learner, a VAE run (directory or weights.pt) whose mean-action policy acts instead of the controller on --learner-share of the control steps, its action held over the step; each step records the clean controller's mean command from its start state")
      ->check(CLI::ExistingPath);
  collect->add_option("--learner-share", c->learner_share, "with --learner: the probability that the learner acts in a control step (DAgger's 1 - beta)")
      ->check(CLI::Range(0.0, 1.0))->capture_default_str();
  collect->add_option("--z-from", c->z_from, "with --learner: demonstrations of the same styles (matched by expert id) whose mu, one drawn per episode, is the learner's z")
      ->check(CLI::ExistingFile);
  collect->add_option("--threads", c->collect.threads, "episodes stepped at once (one core each)")->check(CLI::Range(1, 64))->capture_default_str();
  collect->add_flag("--force", c->force, "replace an existing output file");
  collect->callback([c] { run_collect(*c); });

  auto styles_path = std::make_shared<std::string>();
  CLI::App* styles = demos->add_subcommand("styles", "humanoid: are the styles distinct? a nearest-centroid classifier on per-episode gait statistics, fit on half of each style's episodes, names the other half");
  styles->add_option("--demos", *styles_path, "humanoid demonstration file")->required()->check(CLI::ExistingFile);
  styles->callback([styles_path] { run_styles(*styles_path); });
}

}  // namespace vaegail::cli
