// An RL agent as the batch policy that records episodes (data/record.h): evaluation of
// experts and collection of demonstrations.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "data/record.h"
#include "rl/agent.h"

namespace vaegail {

// conditions[e] is requested episode e's condition (empty rows when the agent has none).
// stochastic: mean + std * noise, the noise drawn from a stream per episode seeded by
// (seed, episode), so recordings do not depend on batching; otherwise the mean action.
BatchPolicy agent_batch_policy(std::shared_ptr<Agent> agent, std::vector<std::vector<float>> conditions,
                               bool stochastic, std::uint64_t seed);

}  // namespace vaegail
