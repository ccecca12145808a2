// vaegail: robust imitation of diverse behaviours (Wang, Merel et al. 2017) as one CLI.
#include <cstdio>
#include <string>

#include "cli/app.h"
#include "util/world.h"

int main(int argc, char** argv) {
  const auto app = vaegail::cli::make_app();
  std::string rank;
  try {
    // Under mpirun (util/world.h) rank 0 speaks for the run; the others only report errors.
    const vaegail::World& world = vaegail::World::get();
    rank = world.prefix();
    if (!world.is_root() && std::freopen("/dev/null", "w", stdout) == nullptr) return 1;
    app->parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app->exit(e);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vaegail: error: %s%s\n", rank.c_str(), e.what());
    return 1;
  }
  return 0;
}
