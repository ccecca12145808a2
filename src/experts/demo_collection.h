// `vaegail demos collect`: roll experts out into one demonstration file. Each episode carries
// its expert id, target speed (context), seed, achieved average speed (mean_com_speed), the
// expert's initial log-std, and held_out = 1 for experts kept out of VAE training (for
// one-shot imitation of unseen demonstrations).
#pragma once

#include <cstdint>
#include <set>
#include <string>
#include <vector>

namespace vaegail {

class Progress;

struct CollectOptions {
  int episodes_per_expert = 20;  // the paper's walker set: 20 per policy
  bool stochastic = false;       // default: mean actions (clean demonstrations, see README)
  std::uint64_t seed = 0;
  int num_envs = 10;
  int threads = 1;
  std::set<std::string> held_out;  // expert ids
};

// Context-conditioned experts cycle through their target speeds episode by episode.
void collect_demos(const std::vector<std::string>& expert_dirs, const std::string& out_path,
                   const CollectOptions& options, Progress* progress = nullptr);

}  // namespace vaegail
