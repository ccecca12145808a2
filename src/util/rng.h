// Seeds and random numbers that are the same on every platform and thread count.
#pragma once

#include <cstdint>
#include <map>
#include <random>

namespace vaegail {

// SplitMix64 finaliser: a well-mixed 64-bit value for each (seed, stream) pair.
inline std::uint64_t derive_seed(std::uint64_t seed, std::uint64_t stream) {
  std::uint64_t z = seed + 0x9E3779B97F4A7C15ULL * (stream + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

// std::uniform_real_distribution and std::normal_distribution differ between standard
// libraries; these are defined here so a seed means the same numbers everywhere.
class Rng {
 public:
  explicit Rng(std::uint64_t seed) : engine_(derive_seed(seed, 0)) {}
  // Uniform in [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  double uniform(double low, double high) { return low + (high - low) * uniform(); }
  // Standard normal by Box-Muller (one value per call; the pair's second half is dropped).
  double normal();
  std::uint64_t next() { return engine_(); }

 private:
  std::mt19937_64 engine_;
};

// One stream per episode, seeded by (seed, episode) and made on first use: a batch policy's
// noise then does not depend on which episodes happen to share a batch.
class EpisodeStreams {
 public:
  explicit EpisodeStreams(std::uint64_t seed) : seed_(seed) {}
  Rng& operator()(int episode) { return streams_.try_emplace(episode, derive_seed(seed_, episode)).first->second; }

 private:
  std::uint64_t seed_;
  std::map<int, Rng> streams_;
};

}  // namespace vaegail
