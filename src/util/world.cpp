#include "util/world.h"

#include <cstdlib>
#include <stdexcept>
#include <type_traits>

#ifdef VAEGAIL_WITH_MPI
// The C API only: the deprecated C++ bindings would need libmpi_cxx.
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>
#endif

namespace vaegail {

namespace {

// Set by OpenMPI's, MPICH's and Slurm's launchers in every process they start.
bool launched_by_mpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE", "PMI_RANK"})
    if (std::getenv(name) != nullptr) return true;
  return false;
}

#ifdef VAEGAIL_WITH_MPI
void check(int code, const char* what) {
  if (code != MPI_SUCCESS) throw std::runtime_error(std::string("MPI: ") + what + " failed");
}
#endif

}  // namespace

bool world_supports_mpi() {
#ifdef VAEGAIL_WITH_MPI
  return true;
#else
  return false;
#endif
}

World& World::get() {
  static World world;
  return world;
}

World::World() {
  if (!launched_by_mpi()) return;
#ifdef VAEGAIL_WITH_MPI
  int provided = 0;
  check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
  initialised_mpi_ = true;
  check(MPI_Comm_rank(MPI_COMM_WORLD, &rank_), "MPI_Comm_rank");
  check(MPI_Comm_size(MPI_COMM_WORLD, &size_), "MPI_Comm_size");
#else
  // Each process would train alone and all would write the same run directory.
  throw std::runtime_error("launched by mpirun, but this vaegail was built without MPI (install libopenmpi-dev and rebuild)");
#endif
}

World::~World() {
#ifdef VAEGAIL_WITH_MPI
  int finalized = 0;
  if (initialised_mpi_ && MPI_Finalized(&finalized) == MPI_SUCCESS && !finalized) MPI_Finalize();
#endif
}

namespace {

// Sums `count` values of one MPI type over MPI_COMM_WORLD, in place.
template <typename T>
void all_reduce_sum(T* values, std::int64_t count) {
#ifdef VAEGAIL_WITH_MPI
  const MPI_Datatype type = std::is_same_v<T, double> ? MPI_DOUBLE : MPI_FLOAT;
  check(MPI_Allreduce(MPI_IN_PLACE, values, static_cast<int>(count), type, MPI_SUM, MPI_COMM_WORLD), "MPI_Allreduce");
#else
  (void)values;
  (void)count;
#endif
}

}  // namespace

void World::sum(double* values, std::int64_t count) const {
  if (size_ > 1 && count > 0) all_reduce_sum(values, count);
}

void World::sum(float* values, std::int64_t count) const {
  if (size_ > 1 && count > 0) all_reduce_sum(values, count);
}

double World::sum(double value) const {
  sum(&value, 1);
  return value;
}

void World::broadcast(std::uint64_t* values, std::int64_t count) const {
  if (size_ == 1 || count == 0) return;
#ifdef VAEGAIL_WITH_MPI
  check(MPI_Bcast(values, static_cast<int>(count), MPI_UINT64_T, 0, MPI_COMM_WORLD), "MPI_Bcast");
#endif
}

void World::barrier() const {
  if (size_ == 1) return;
#ifdef VAEGAIL_WITH_MPI
  check(MPI_Barrier(MPI_COMM_WORLD), "MPI_Barrier");
#endif
}

std::string World::prefix() const {
  return size_ == 1 ? "" : "rank " + std::to_string(rank_) + " of " + std::to_string(size_) + ": ";
}

}  // namespace vaegail
