// Test support: a test binary runs one of its own cases on K ranks under mpirun (the ranks'
// program, told what to do through environment variables) and then compares what they wrote
// with one process. Header-only: tests of several stages include it.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <map>
#include <sstream>
#include <string>

#include "util/world.h"

namespace vaegail {

// Whether ranks can run here: this build has MPI and mpirun is on the PATH.
inline bool have_mpirun() { return world_supports_mpi() && std::system("command -v mpirun > /dev/null 2>&1") == 0; }

// Runs this test binary's case `test_case` ("Suite.Name") on `ranks` ranks, each with
// `variables` (name -> value) in its environment, as root with OpenMPI's permission (CI runs as
// root). Returns "" when every rank succeeded, else the command and mpirun's output (kept in `log`).
inline std::string run_case_on_ranks(int ranks, const std::string& test_case,
                                     const std::map<std::string, std::string>& variables,
                                     const std::filesystem::path& log) {
  std::ostringstream command;
  // OpenMPI leaks by design: in the sanitizer build (docs/sanitizers.md) the ranks run without
  // the leak check, which would fail them at exit; this process keeps it.
  command << "ASAN_OPTIONS=${ASAN_OPTIONS:-}:detect_leaks=0 OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 ";
  for (const auto& [name, value] : variables) command << name << "=" << std::quoted(value) << " ";
  command << "mpirun -np " << ranks << " --oversubscribe";
  for (const auto& [name, value] : variables) command << " -x " << name;
  command << " " << std::filesystem::read_symlink("/proc/self/exe") << " --gtest_filter=" << test_case << " > "
          << log << " 2>&1";
  if (std::system(command.str().c_str()) == 0) return "";
  std::ifstream in(log);
  return command.str() + "\n" + std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace vaegail
