#include "experts/cma_es.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <nlohmann/json.hpp>

namespace vaegail {
namespace {

double sphere(const std::vector<double>& x) {
  double s = 0;
  for (double xi : x) s += xi * xi;
  return s;
}

double rosenbrock(const std::vector<double>& x) {
  double s = 0;
  for (size_t i = 0; i + 1 < x.size(); ++i)
    s += 100 * std::pow(x[i + 1] - x[i] * x[i], 2) + std::pow(1 - x[i], 2);
  return s;
}

// Runs until the best cost is under `target` or `max_generations` pass; returns generations used.
int minimise(CmaEs& es, const std::function<double(const std::vector<double>&)>& f, double target,
             int max_generations) {
  while (es.generation() < max_generations && es.best_cost() > target) {
    std::vector<double> costs;
    for (const auto& x : es.ask()) costs.push_back(f(x));
    es.tell(costs);
  }
  return es.generation();
}

TEST(CmaEs, MinimisesTheSphere) {
  CmaEs es(std::vector<double>(10, 3.0), {.population = 0, .sigma = 1.0, .seed = 1});
  EXPECT_EQ(es.population(), 10);  // 4 + floor(3 ln 10)
  const int generations = minimise(es, sphere, 1e-10, 1000);
  EXPECT_LT(es.best_cost(), 1e-10);
  // Linear convergence: the cost falls by a constant factor per generation, so 1e-10 from 90
  // takes on the order of a hundred generations at n = 10 (a broken step-size rule stalls or
  // needs thousands).
  EXPECT_LT(generations, 400);
  for (double m : es.mean()) EXPECT_NEAR(m, 0.0, 1e-4);
}

TEST(CmaEs, MinimisesRosenbrock) {
  // The narrow curved valley is what covariance adaptation is for: the search must learn to
  // step along it to reach (1, ..., 1).
  CmaEs es(std::vector<double>(5, 0.0), {.population = 0, .sigma = 0.5, .seed = 2});
  minimise(es, rosenbrock, 1e-10, 3000);
  EXPECT_LT(es.best_cost(), 1e-10);
  for (double x : es.best()) EXPECT_NEAR(x, 1.0, 1e-4);
}

TEST(CmaEs, AdaptsItsCovarianceToAnIllConditionedBowl) {
  // f = x0^2 + 1e4 x1^2: after adaptation, C's ratio of variances follows the bowl's 1e4.
  const auto ellipse = [](const std::vector<double>& x) { return x[0] * x[0] + 1e4 * x[1] * x[1]; };
  CmaEs es({1.0, 1.0}, {.population = 0, .sigma = 0.5, .seed = 3});
  minimise(es, ellipse, 0.0, 150);
  const auto state = es.state();
  const auto& c = state.at("covariance");
  const double ratio = c[0].get<double>() / c[3].get<double>();
  EXPECT_GT(ratio, 1e3);
  EXPECT_LT(ratio, 1e5);
}

TEST(CmaEs, TheSameSeedAndCostsGiveTheSameSearch) {
  CmaEs a(std::vector<double>(4, 1.0), {.population = 8, .sigma = 0.3, .seed = 7});
  CmaEs b(std::vector<double>(4, 1.0), {.population = 8, .sigma = 0.3, .seed = 7});
  CmaEs c(std::vector<double>(4, 1.0), {.population = 8, .sigma = 0.3, .seed = 8});
  minimise(a, rosenbrock, 0.0, 20);
  minimise(b, rosenbrock, 0.0, 20);
  minimise(c, rosenbrock, 0.0, 20);
  EXPECT_EQ(a.mean(), b.mean());
  EXPECT_NE(a.mean(), c.mean());
}

TEST(CmaEs, AResumedSearchEqualsTheUninterruptedOne) {
  CmaEs whole(std::vector<double>(6, 2.0), {.population = 0, .sigma = 0.5, .seed = 4});
  minimise(whole, rosenbrock, 0.0, 40);
  CmaEs first(std::vector<double>(6, 2.0), {.population = 0, .sigma = 0.5, .seed = 4});
  minimise(first, rosenbrock, 0.0, 15);
  CmaEs resumed = CmaEs::from_state(nlohmann::json::parse(first.state().dump()));
  minimise(resumed, rosenbrock, 0.0, 40);
  EXPECT_EQ(resumed.mean(), whole.mean());
  EXPECT_EQ(resumed.sigma(), whole.sigma());
  EXPECT_EQ(resumed.best(), whole.best());
  EXPECT_EQ(resumed.ask(), whole.ask());
}

TEST(CmaEs, AskIsStableUntilTell) {
  CmaEs es({0.0, 0.0, 0.0}, {.population = 6, .sigma = 1.0, .seed = 5});
  const auto first = es.ask();
  EXPECT_EQ(es.ask(), first);
  es.tell(std::vector<double>(6, 1.0));
  EXPECT_NE(es.ask(), first);
}

TEST(CmaEs, RefusesBadInput) {
  EXPECT_THROW(CmaEs({}, {}), std::invalid_argument);
  EXPECT_THROW(CmaEs({1.0}, {.population = 0, .sigma = 0.0, .seed = 0}), std::invalid_argument);
  CmaEs es({0.0, 0.0}, {.population = 6, .sigma = 1.0, .seed = 0});
  EXPECT_THROW(es.tell(std::vector<double>(6, 1.0)), std::invalid_argument);  // no ask() yet
  es.ask();
  EXPECT_THROW(es.tell(std::vector<double>(5, 1.0)), std::invalid_argument);
  EXPECT_THROW(es.tell(std::vector<double>(6, std::nan(""))), std::invalid_argument);
  EXPECT_THROW(CmaEs::from_state(nlohmann::json{{"mean", {1.0}}}), std::invalid_argument);
}

}  // namespace
}  // namespace vaegail
