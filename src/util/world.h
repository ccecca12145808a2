// The processes of one training run. A plain `vaegail` is a world of one process, in which every
// collective below returns at once and leaves its data as it is. Launched by `mpirun -np K` (and
// built with MPI), it is MPI_COMM_WORLD: each process (rank) steps its own share of the
// environments and the trainers sum their per-rank quantities here, so that the K ranks compute
// what one process with all the environments would (src/rl/distributed.h).
//
// Only the calling thread of a rank talks to MPI (the thread pools never do); a rank that throws
// ends its process, and mpirun then ends the others.
#pragma once

#include <cstdint>
#include <string>

namespace vaegail {

class World {
 public:
  // The run's world: initialises MPI on first use when the process was launched by an MPI
  // launcher (its environment says so), else a world of one.
  static World& get();

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool is_root() const { return rank_ == 0; }
  bool distributed() const { return size_ > 1; }

  // In place: values[i] becomes the sum of values[i] over the ranks.
  void sum(double* values, std::int64_t count) const;
  void sum(float* values, std::int64_t count) const;
  double sum(double value) const;
  // In place: every rank's values become rank 0's.
  void broadcast(std::uint64_t* values, std::int64_t count) const;
  void barrier() const;

  // "rank R of K: " under mpirun (for messages), "" in a world of one.
  std::string prefix() const;

  World(const World&) = delete;
  World& operator=(const World&) = delete;

 private:
  World();
  ~World();
  int rank_ = 0;
  int size_ = 1;
  bool initialised_mpi_ = false;
};

// Whether this build can run under mpirun (CMake found MPI).
bool world_supports_mpi();

}  // namespace vaegail
