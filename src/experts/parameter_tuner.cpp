#include "experts/parameter_tuner.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <numeric>
#include <stdexcept>

#include "experts/cma_es.h"
#include "util/atomic_file.h"
#include "util/json_file.h"
#include "util/progress.h"
#include "util/thread_pool.h"

namespace vaegail {
namespace {

// What a resumed search must share with the one that wrote the state.
nlohmann::json search_identity(const std::vector<TunedParameter>& tuned, const TuneOptions& options) {
  nlohmann::json names = nlohmann::json::array();
  for (const auto& p : tuned) names.push_back({p.name, p.low, p.high});
  return {{"tuned", names}, {"population", options.population}, {"sigma", options.sigma}, {"seed", options.seed}};
}

struct GenerationRecord {
  int generation = 0;
  double best_cost = 0, mean_cost = 0, sigma = 0, seconds = 0;
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(GenerationRecord, generation, best_cost, mean_cost, sigma, seconds)

void write_metrics(const std::string& path, const std::vector<GenerationRecord>& history) {
  std::string csv = "generation,best_cost,mean_cost,sigma,seconds\n";
  for (const auto& r : history)
    csv += fmt::format("{},{:.9g},{:.9g},{:.9g},{:.3f}\n", r.generation, r.best_cost, r.mean_cost, r.sigma, r.seconds);
  write_file_atomically(path, csv);
}

}  // namespace

std::vector<double> normalise(const nlohmann::json& start, const std::vector<TunedParameter>& tuned) {
  std::vector<double> u;
  for (const auto& p : tuned) {
    if (!start.contains(p.name)) throw std::invalid_argument("tuned parameter '" + p.name + "' is not a parameter");
    if (!start.at(p.name).is_number())
      throw std::invalid_argument("tuned parameter '" + p.name + "' is not a number");
    if (!(p.high > p.low))
      throw std::invalid_argument(fmt::format("tuned parameter '{}': empty range [{}, {}]", p.name, p.low, p.high));
    u.push_back((start.at(p.name).get<double>() - p.low) / (p.high - p.low));
  }
  return u;
}

nlohmann::json denormalise(const nlohmann::json& start, const std::vector<TunedParameter>& tuned,
                           const std::vector<double>& u, double* outside) {
  nlohmann::json parameters = start;
  double distance = 0;
  for (size_t i = 0; i < tuned.size(); ++i) {
    const double inside = std::clamp(u[i], 0.0, 1.0);
    distance += (u[i] - inside) * (u[i] - inside);
    parameters[tuned[i].name] = tuned[i].low + inside * (tuned[i].high - tuned[i].low);
  }
  if (outside) *outside = distance;
  return parameters;
}

TuneResult tune_parameters(const nlohmann::json& fresh_start, const std::vector<TunedParameter>& tuned,
                           const TuneOptions& options, const ParameterCost& cost, const std::string& state_path,
                           const std::string& metrics_path) {
  if (tuned.empty()) throw std::invalid_argument("nothing to tune: no parameters named");
  const nlohmann::json identity = search_identity(tuned, options);
  nlohmann::json start = fresh_start;
  CmaEs es(normalise(start, tuned), {.population = options.population, .sigma = options.sigma, .seed = options.seed});
  std::vector<GenerationRecord> history;
  TuneResult result;
  if (std::filesystem::exists(state_path)) {
    const nlohmann::json state = read_json_file(state_path);
    if (state.value("identity", nlohmann::json()) != identity)
      throw std::runtime_error(state_path + ": a search with other parameters, bounds or options (use another state file)");
    start = state.at("start");
    es = CmaEs::from_state(state.at("cma"));
    history = state.at("history").get<std::vector<GenerationRecord>>();
    result.resumed = fmt::format("resumed at generation {}", es.generation());
  }

  ThreadPool pool(options.jobs);
  Progress progress("tune", options.generations, "gen");
  progress.resume(es.generation());
  while (es.generation() < options.generations) {
    const auto began = std::chrono::steady_clock::now();
    const auto& candidates = es.ask();
    std::vector<double> costs(candidates.size());
    pool.parallel_for(static_cast<int>(candidates.size()), [&](int k) {
      double outside = 0;
      const nlohmann::json parameters = denormalise(start, tuned, candidates[k], &outside);
      costs[k] = cost(parameters, k) + kBoundPenalty * outside;
    });
    es.tell(costs);
    history.push_back({.generation = es.generation(),
                       .best_cost = es.best_cost(),
                       .mean_cost = std::accumulate(costs.begin(), costs.end(), 0.0) / costs.size(),
                       .sigma = es.sigma(),
                       .seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count()});
    // The state first: a kill between the two writes leaves a CSV one row short, which the
    // resumed run rewrites whole from the state's history.
    write_file_atomically(state_path,
                          nlohmann::json{{"identity", identity}, {"start", start}, {"cma", es.state()}, {"history", history}}.dump(1));
    write_metrics(metrics_path, history);
    progress.advance();
    progress.set_status(fmt::format("best {:.4g}  sigma {:.3g}", es.best_cost(), es.sigma()));
  }
  progress.finish();
  if (!history.empty()) write_metrics(metrics_path, history);  // mends a CSV a kill left a row short
  result.parameters = es.best().empty() ? start : denormalise(start, tuned, es.best());
  result.cost = es.best_cost();
  result.generations = es.generation();
  return result;
}

}  // namespace vaegail
