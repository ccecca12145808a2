#include "vae/vae_config.h"

#include <nlohmann/json.hpp>

#include <stdexcept>

#include "util/atomic_file.h"

namespace vaegail::vae {

// config.json: every field under its own name (from_json below says what a missing key takes).
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(VaeConfig, name, state_dim, action_dim, lstm_hidden, latent_dim,
                                                action_hidden, wavenet_channels, wavenet_layers, mixture_components,
                                                position_embedding, action_relative_to_state,
                                                action_std_depends_on_state, policy_state_std_floor, encoder_state_indices, learning_rate,
                                                batch_size, kl_weight, weight_decay, encoder_input_noise,
                                                lr_decay_epochs)

namespace {

using nlohmann::json;

VaeConfig sized(std::string name, int state_dim, int action_dim, int lstm, int latent,
                std::vector<int> action_hidden, int channels, int layers) {
  VaeConfig c;
  c.name = std::move(name);
  c.state_dim = state_dim;
  c.action_dim = action_dim;
  c.lstm_hidden = lstm;
  c.latent_dim = latent;
  c.action_hidden = std::move(action_hidden);
  c.wavenet_channels = channels;
  c.wavenet_layers = layers;
  return c;
}

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("VaeConfig: " + what);
}

}  // namespace

VaeConfig VaeConfig::walker(int state_dim, int action_dim) {
  return sized("walker", state_dim, action_dim, 200, 20, {200, 200}, 32, 6);
}

VaeConfig VaeConfig::arm(int state_dim, int action_dim) {
  return sized("arm", state_dim, action_dim, 500, 30, {400, 300, 200}, 32, 10);
}

VaeConfig VaeConfig::humanoid(int state_dim, int action_dim) {
  return sized("humanoid", state_dim, action_dim, 500, 30, {400, 300, 200}, 32, 14);
}

VaeConfig VaeConfig::preset(const std::string& name, int state_dim, int action_dim) {
  if (name == "walker") return walker(state_dim, action_dim);
  if (name == "arm" || name == "jaco") return arm(state_dim, action_dim);
  if (name == "humanoid") return humanoid(state_dim, action_dim);
  throw std::invalid_argument("VaeConfig: unknown preset '" + name +
                              "' (walker, arm, jaco, humanoid)");
}

void VaeConfig::validate() const {
  require(state_dim >= 1, "state_dim must be >= 1");
  require(action_dim >= 1, "action_dim must be >= 1");
  require(lstm_hidden >= 1, "lstm_hidden must be >= 1");
  require(latent_dim >= 1, "latent_dim must be >= 1");
  for (int h : action_hidden) require(h >= 1, "action_hidden sizes must be >= 1");
  require(wavenet_channels >= 1, "wavenet_channels must be >= 1");
  require(wavenet_layers >= 1, "wavenet_layers must be >= 1");
  require(mixture_components >= 1, "mixture_components must be >= 1");
  require(learning_rate > 0, "learning_rate must be > 0");
  require(batch_size >= 1, "batch_size must be >= 1");
  require(kl_weight >= 0, "kl_weight must be >= 0");
  require(weight_decay >= 0, "weight_decay must be >= 0");
  require(encoder_input_noise >= 0, "encoder_input_noise must be >= 0");
  require(policy_state_std_floor >= 0, "policy_state_std_floor must be >= 0");
  require(lr_decay_epochs >= 0, "lr_decay_epochs must be >= 0");
  for (int k : encoder_state_indices)
    require(k >= 0 && k < state_dim, "encoder_state_indices must lie in [0, state_dim)");
  require(action_relative_to_state.empty() ||
              static_cast<int>(action_relative_to_state.size()) == action_dim,
          "action_relative_to_state must be empty or have action_dim entries");
  for (int k : action_relative_to_state)
    require(k >= 0 && k < state_dim, "action_relative_to_state entries must be state indices");
}

std::string VaeConfig::to_json() const { return json(*this).dump(2) + "\n"; }

VaeConfig VaeConfig::from_json(const std::string& text, const VaeConfig& defaults) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {
    throw std::invalid_argument(std::string("VaeConfig: not JSON: ") + e.what());
  }
  require(j.is_object(), "JSON must be an object");
  // One key at a time, so that an error names the unknown key or the bad value.
  VaeConfig c = defaults;
  for (const auto& [key, value] : j.items()) {
    json fields = c;
    if (!fields.contains(key)) throw std::invalid_argument("VaeConfig: unknown key '" + key + "'");
    fields[key] = value;
    try {
      c = fields.get<VaeConfig>();
    } catch (const json::exception& e) {
      throw std::invalid_argument("VaeConfig: bad value for '" + key + "': " + e.what());
    }
  }
  c.validate();
  return c;
}

VaeConfig VaeConfig::from_json(const std::string& text) { return from_json(text, walker()); }

VaeConfig VaeConfig::load(const std::string& path) { return load(path, walker()); }

void VaeConfig::save(const std::string& path) const { write_file_atomically(path, to_json()); }

VaeConfig VaeConfig::load(const std::string& path, const VaeConfig& defaults) {
  try {
    return from_json(read_file(path), defaults);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(path + ": " + e.what());
  }
}

bool VaeConfig::operator==(const VaeConfig& o) const { return json(*this) == json(o); }

}  // namespace vaegail::vae
