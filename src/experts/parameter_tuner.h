// Tuning a few named parameters of a JSON parameter object by CMA-ES (experts/cma_es.h): the
// search behind `vaegail experts tune`, which scores a gait controller's style over simulated
// episodes. The tuner knows nothing of gaits: it reads and writes parameters by name in a JSON
// object (the controller's parameter struct as JSON), so that any struct with JSON fields can be
// tuned, and asks a cost function for each candidate.
//
// The search runs in normalised coordinates u, one per tuned parameter, u = 0 at its low bound
// and 1 at its high bound, so that one step size suits parameters of different units. A
// candidate outside [0, 1] is evaluated at its nearest point inside (repair) and pays
// kBoundPenalty times its squared distance outside (Hansen's tutorial, boundary handling by
// repair and penalty), which keeps the mean from wandering off.
//
// Resumable: after every generation the state (CMA-ES, the history of costs) is written
// atomically to STATE_PATH (JSON) and the metrics to a CSV beside it, rewritten whole from the
// history, so that a run killed at any moment resumes with the same command and ends where an
// uninterrupted run ends (the costs being deterministic functions of the candidates).
#pragma once

#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace vaegail {

struct TunedParameter {
  std::string name;
  double low = 0, high = 1;
};

struct TuneOptions {
  int generations = 40;
  int population = 0;  // 0: CMA-ES's default for the dimension
  double sigma = 0.2;  // initial step size, in normalised units (a fifth of each range)
  std::uint64_t seed = 0;
  int jobs = 1;        // candidates scored at once, one thread each
};

// The cost of one candidate (lower is better): called with the full parameter object, the
// tuned names set; `candidate` numbers the candidates of a generation (for seeding, logging).
// Called from `jobs` threads at once: it must not share mutable state between calls.
using ParameterCost = std::function<double(const nlohmann::json& parameters, int candidate)>;

struct TuneResult {
  nlohmann::json parameters;  // the best candidate seen
  double cost = 0;
  int generations = 0;        // generations run in total, earlier runs of a resumed search included
  std::string resumed;        // "" for a fresh search, else "resumed at generation G"
};

inline constexpr double kBoundPenalty = 1e3;

// The parameters of `start` named by `tuned`, in its order, as normalised coordinates. Throws
// naming the parameter when `start` lacks it, it is not a number, or its bounds are empty.
std::vector<double> normalise(const nlohmann::json& start, const std::vector<TunedParameter>& tuned);
// `start` with the tuned parameters set from normalised coordinates, clamped into their bounds;
// `outside` (when given) receives the squared distance of u outside [0, 1]^n.
nlohmann::json denormalise(const nlohmann::json& start, const std::vector<TunedParameter>& tuned,
                           const std::vector<double>& u, double* outside = nullptr);

// Searches from `start` for options.generations generations (in total, counting a resumed
// search's earlier ones), scoring each candidate with `cost`. A state at `state_path` resumes
// the search when it was made with the same tuned parameters, bounds and options (the number of
// generations aside: more carries on), and throws std::runtime_error naming the file otherwise;
// a resumed search starts from the state's start, not from `start`, so that the same command
// still resumes after its result has been written over the file it started from. The metrics CSV (generation, best_cost,
// mean_cost, sigma, seconds) is written next to it as metrics_path. A progress bar shows the
// generations and the best cost.
TuneResult tune_parameters(const nlohmann::json& start, const std::vector<TunedParameter>& tuned,
                           const TuneOptions& options, const ParameterCost& cost, const std::string& state_path,
                           const std::string& metrics_path);

}  // namespace vaegail
