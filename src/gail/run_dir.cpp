#include "gail/run_dir.h"

#include <filesystem>
#include <stdexcept>

#include "util/atomic_file.h"
#include "util/checkpoint_file.h"

namespace vaegail {

void check_or_write_config(const std::string& path, const nlohmann::json& config,
                           const std::vector<std::string>& resumable_keys,
                           const std::function<nlohmann::json(const nlohmann::json&)>& normalize) {
  if (std::filesystem::exists(path)) {
    auto stored = normalize(nlohmann::json::parse(read_file(path))), wanted = config;
    for (const auto& key : resumable_keys) {
      stored.erase(key);
      wanted.erase(key);
    }
    const auto diff = nlohmann::json::diff(stored, wanted);
    if (!diff.empty())
      throw std::invalid_argument(path + ": the run was started with other settings (" +
                                  diff.front().at("path").get<std::string>() + "); use a new run directory");
  }
  write_file_atomically(path, config.dump(2));
}

nlohmann::json read_run_config_json(const std::string& run_dir) {
  const std::string path = run_dir + "/config.json";
  if (!std::filesystem::exists(path)) throw std::runtime_error(path + ": no such file (not a run directory?)");
  try {
    return nlohmann::json::parse(read_file(path));
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
}

std::string run_checkpoint(const std::string& run_dir) { return run_dir + "/checkpoints/latest.pt"; }

namespace {

// The run directory of a trainer checkpoint, RUN/checkpoints/NAME.pt.
std::string run_dir_of_checkpoint(const std::string& path) {
  const auto run = std::filesystem::path(path).parent_path().parent_path();
  return run.empty() ? "." : run.string();
}

}  // namespace

RunFile open_run(const std::string& run, const std::string& kind) {
  RunFile file;
  file.path = model_file(run);
  std::string config;
  read_checkpoint(file.path, [&](const std::string& path) {
    torch::serialize::InputArchive archive;
    archive.load_from(path);
    c10::IValue value;
    if (!archive.try_read("kind", value)) return;  // a trainer's checkpoint
    file.kind = value.toStringRef();
    archive.read("config", value);
    config = value.toStringRef();
    if (archive.try_read("vae_config", value)) file.vae_config = value.toStringRef();
  });
  if (file.kind.empty()) {
    file.config = read_run_config_json(run_dir_of_checkpoint(file.path));
    return file;
  }
  if (file.kind != kind)
    throw std::runtime_error(file.path + ": the weights of a " + file.kind + " run, not of a " + kind + " run");
  file.config = nlohmann::json::parse(config);
  return file;
}

void load_run_agent(const std::string& run, Agent& agent, torch::Device device) {
  read_checkpoint(model_file(run), [&](const std::string& path) {
    torch::serialize::InputArchive root, archive;
    root.load_from(path, device);
    root.read("agent", archive);
    agent.load(archive);
  });
  agent.eval();
}

void save_agent_weights(const std::string& path, const std::string& kind, const nlohmann::json& config,
                        const Agent& agent, const std::string& vae_config) {
  write_checkpoint(path, [&](std::ostream& out) {
    torch::serialize::OutputArchive root, archive;
    agent.save(archive);
    root.write("kind", c10::IValue(kind));
    root.write("config", c10::IValue(config.dump()));
    if (!vae_config.empty()) root.write("vae_config", c10::IValue(vae_config));
    root.write("agent", archive);
    root.save_to(out);
  });
}

}  // namespace vaegail
