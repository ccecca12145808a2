#include "vae/vae_config.h"

#include <nlohmann/json.hpp>

#include <stdexcept>

#include "util/atomic_file.h"

namespace vaegail::vae {

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
  require(lr_decay_epochs >= 0, "lr_decay_epochs must be >= 0");
  for (int k : encoder_state_indices)
    require(k >= 0 && k < state_dim, "encoder_state_indices must lie in [0, state_dim)");
  require(action_relative_to_state.empty() ||
              static_cast<int>(action_relative_to_state.size()) == action_dim,
          "action_relative_to_state must be empty or have action_dim entries");
  for (int k : action_relative_to_state)
    require(k >= 0 && k < state_dim, "action_relative_to_state entries must be state indices");
}

std::string VaeConfig::to_json() const {
  json j = {{"name", name},
            {"state_dim", state_dim},
            {"action_dim", action_dim},
            {"lstm_hidden", lstm_hidden},
            {"latent_dim", latent_dim},
            {"action_hidden", action_hidden},
            {"wavenet_channels", wavenet_channels},
            {"wavenet_layers", wavenet_layers},
            {"mixture_components", mixture_components},
            {"position_embedding", position_embedding},
            {"action_relative_to_state", action_relative_to_state},
            {"action_std_depends_on_state", action_std_depends_on_state},
            {"encoder_state_indices", encoder_state_indices},
            {"learning_rate", learning_rate},
            {"batch_size", batch_size},
            {"kl_weight", kl_weight},
            {"weight_decay", weight_decay},
            {"encoder_input_noise", encoder_input_noise},
            {"lr_decay_epochs", lr_decay_epochs}};
  return j.dump(2) + "\n";
}

VaeConfig VaeConfig::from_json(const std::string& text, const VaeConfig& defaults) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {
    throw std::invalid_argument(std::string("VaeConfig: not JSON: ") + e.what());
  }
  require(j.is_object(), "JSON must be an object");
  VaeConfig c = defaults;
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string& key = it.key();
    try {
      if (key == "name") c.name = it->get<std::string>();
      else if (key == "state_dim") c.state_dim = it->get<int>();
      else if (key == "action_dim") c.action_dim = it->get<int>();
      else if (key == "lstm_hidden") c.lstm_hidden = it->get<int>();
      else if (key == "latent_dim") c.latent_dim = it->get<int>();
      else if (key == "action_hidden") c.action_hidden = it->get<std::vector<int>>();
      else if (key == "wavenet_channels") c.wavenet_channels = it->get<int>();
      else if (key == "wavenet_layers") c.wavenet_layers = it->get<int>();
      else if (key == "mixture_components") c.mixture_components = it->get<int>();
      else if (key == "position_embedding") c.position_embedding = it->get<bool>();
      else if (key == "action_relative_to_state")
        c.action_relative_to_state = it->get<std::vector<int>>();
      else if (key == "action_std_depends_on_state")
        c.action_std_depends_on_state = it->get<bool>();
      else if (key == "encoder_state_indices")
        c.encoder_state_indices = it->get<std::vector<int>>();
      else if (key == "learning_rate") c.learning_rate = it->get<double>();
      else if (key == "batch_size") c.batch_size = it->get<int>();
      else if (key == "kl_weight") c.kl_weight = it->get<double>();
      else if (key == "weight_decay") c.weight_decay = it->get<double>();
      else if (key == "encoder_input_noise") c.encoder_input_noise = it->get<double>();
      else if (key == "lr_decay_epochs") c.lr_decay_epochs = it->get<int>();
      else throw std::invalid_argument("VaeConfig: unknown key '" + key + "'");
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

bool VaeConfig::operator==(const VaeConfig& o) const {
  return name == o.name && state_dim == o.state_dim && action_dim == o.action_dim &&
         lstm_hidden == o.lstm_hidden && latent_dim == o.latent_dim &&
         action_hidden == o.action_hidden && wavenet_channels == o.wavenet_channels &&
         wavenet_layers == o.wavenet_layers && mixture_components == o.mixture_components &&
         position_embedding == o.position_embedding &&
         action_relative_to_state == o.action_relative_to_state &&
         action_std_depends_on_state == o.action_std_depends_on_state &&
         encoder_state_indices == o.encoder_state_indices && learning_rate == o.learning_rate &&
         batch_size == o.batch_size && kl_weight == o.kl_weight && weight_decay == o.weight_decay &&
         encoder_input_noise == o.encoder_input_noise && lr_decay_epochs == o.lr_decay_epochs;
}

}  // namespace vaegail::vae
