#include "env/registry.h"

#include <stdexcept>

#include "env/arm.h"
#include "env/generic_task.h"
#include "env/humanoid.h"
#include "env/walker.h"

namespace vaegail {

namespace {
bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}
}  // namespace

std::vector<std::string> builtin_tasks() { return {"walker", "arm", "humanoid"}; }

std::unique_ptr<Env> make_env(const EnvRequest& request) {
  if (request.task == "walker") {
    WalkerOptions o;
    o.terminate_on_fall = request.terminate_on_fall;
    if (request.episode_length > 0) o.episode_length = request.episode_length;
    return std::make_unique<WalkerEnv>(o);
  }
  if (request.task == "arm") {
    ArmOptions o;
    if (request.episode_length > 0) o.episode_length = request.episode_length;
    return std::make_unique<ArmEnv>(o);
  }
  if (request.task == "humanoid") {
    HumanoidOptions o;
    o.terminate_on_fall = request.terminate_on_fall;
    if (request.episode_length > 0) o.episode_length = request.episode_length;
    return std::make_unique<HumanoidEnv>(o);
  }
  if (!request.mjcf_text.empty() || ends_with(request.task, ".xml")) {
    GenericTaskOptions o;
    o.frame_skip = request.frame_skip;
    o.episode_length = request.episode_length;
    o.terminate_on_fall = request.terminate_on_fall;
    o.context_names = request.context_names;
    o.control_timestep = request.control_timestep;
    return std::make_unique<GenericTaskEnv>(request.mjcf_text.empty()
                                                ? MujocoModel::from_file(request.task)
                                                : MujocoModel::from_xml(request.task, request.mjcf_text),
                                            o);
  }
  std::string known;
  for (const auto& t : builtin_tasks()) known += (known.empty() ? "" : ", ") + t;
  throw std::invalid_argument("unknown task '" + request.task + "' (built in: " + known +
                              "; or the path of an MJCF .xml file)");
}

}  // namespace vaegail
