#include "vae/vae_config.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace vaegail::vae {
namespace {

TEST(VaeConfigTest, PresetsAreTable1) {
  const auto w = VaeConfig::walker();
  EXPECT_EQ(w.state_dim, 18);
  EXPECT_EQ(w.action_dim, 6);
  EXPECT_EQ(w.lstm_hidden, 200);
  EXPECT_EQ(w.latent_dim, 20);
  EXPECT_EQ(w.action_hidden, (std::vector<int>{200, 200}));
  EXPECT_EQ(w.wavenet_channels, 32);
  EXPECT_EQ(w.wavenet_layers, 6);

  const auto a = VaeConfig::arm(24, 9);
  EXPECT_EQ(a.state_dim, 24);
  EXPECT_EQ(a.lstm_hidden, 500);
  EXPECT_EQ(a.latent_dim, 30);
  EXPECT_EQ(a.action_hidden, (std::vector<int>{400, 300, 200}));
  EXPECT_EQ(a.wavenet_channels, 32);
  EXPECT_EQ(a.wavenet_layers, 10);

  const auto h = VaeConfig::humanoid(137, 56);
  EXPECT_EQ(h.lstm_hidden, 500);
  EXPECT_EQ(h.latent_dim, 30);
  EXPECT_EQ(h.action_hidden, (std::vector<int>{400, 300, 200}));
  EXPECT_EQ(h.wavenet_layers, 14);

  EXPECT_EQ(VaeConfig::preset("jaco", 24, 9), a);
  EXPECT_THROW(VaeConfig::preset("cheetah", 1, 1), std::invalid_argument);
  EXPECT_EQ(w.mixture_components, 5);
  EXPECT_EQ(w.kl_weight, 1.0);
}

TEST(VaeConfigTest, JsonRoundTrip) {
  auto c = VaeConfig::humanoid(130, 56);
  c.mixture_components = 3;
  c.position_embedding = false;
  c.learning_rate = 3e-4;
  c.kl_weight = 0.5;
  c.action_relative_to_state.assign(56, 3);
  c.action_std_depends_on_state = false;
  c.weight_decay = 1e-5;
  c.encoder_input_noise = 0.3;
  c.encoder_state_indices = {0, 5, 129};
  c.lr_decay_epochs = 30;
  EXPECT_EQ(VaeConfig::from_json(c.to_json()), c);
}

TEST(VaeConfigTest, ActionOffsetsNeedOneStateIndexPerAction) {
  const auto arm = VaeConfig::arm(21, 9);
  EXPECT_NO_THROW(VaeConfig::from_json(R"({"action_relative_to_state": [0,1,2,3,4,5,6,7,20]})", arm));
  EXPECT_THROW(VaeConfig::from_json(R"({"action_relative_to_state": [0, 1]})", arm),
               std::invalid_argument);
  EXPECT_THROW(VaeConfig::from_json(R"({"action_relative_to_state": [0,1,2,3,4,5,6,7,21]})", arm),
               std::invalid_argument);
  EXPECT_NO_THROW(VaeConfig::from_json(R"({"encoder_state_indices": [18, 19, 20]})", arm));
  EXPECT_THROW(VaeConfig::from_json(R"({"encoder_state_indices": [18, 21]})", arm), std::invalid_argument);
}

TEST(VaeConfigTest, MissingKeysKeepDefaultsUnknownKeysThrow) {
  const auto c = VaeConfig::from_json(R"({"latent_dim": 7, "action_hidden": [3, 4]})");
  EXPECT_EQ(c.latent_dim, 7);
  EXPECT_EQ(c.action_hidden, (std::vector<int>{3, 4}));
  EXPECT_EQ(c.lstm_hidden, 200);
  const auto arm = VaeConfig::from_json(R"({"state_dim": 5})", VaeConfig::arm(9, 2));
  EXPECT_EQ(arm.lstm_hidden, 500);
  EXPECT_EQ(arm.state_dim, 5);
  EXPECT_THROW(VaeConfig::from_json(R"({"latnet_dim": 7})"), std::invalid_argument);
  EXPECT_THROW(VaeConfig::from_json(R"({"latent_dim": "seven"})"), std::invalid_argument);
  EXPECT_THROW(VaeConfig::from_json(R"({"latent_dim": 0})"), std::invalid_argument);
  EXPECT_THROW(VaeConfig::from_json("not json"), std::invalid_argument);
}

// Each field is read from its key and counts for ==: a config differing in any one of them differs.
TEST(VaeConfigTest, EveryFieldIsReadAndCompared) {
  using nlohmann::json;
  const VaeConfig c = VaeConfig::walker();
  const json fields = json::parse(c.to_json());
  EXPECT_EQ(fields.size(), 20u);
  for (const auto& [key, value] : fields.items()) {
    // Another value of the field's type that the checks accept.
    const json other = value.is_boolean()  ? json(!value.get<bool>())
                       : value.is_string() ? json(value.get<std::string>() + "2")
                       : value.is_array()  ? json(std::vector<int>(c.action_dim, 1))
                                           : json(value.get<double>() + 1);
    const VaeConfig changed = VaeConfig::from_json(json{{key, other}}.dump(), c);
    EXPECT_EQ(json::parse(changed.to_json()).at(key), other) << key;
    EXPECT_NE(changed, c) << key;
  }
}

TEST(VaeConfigTest, ABadValueIsReportedWithItsKey) {
  try {
    VaeConfig::from_json(R"({"latent_dim": 7, "kl_weight": "high"})");
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("bad value for 'kl_weight'"), std::string::npos) << e.what();
  }
}

// configs/walker_vae_root_encoder.json: the encoder reads the walker's root (env/walker.h's layout:
// 0 height, 1-2 pitch, 9-11 root velocities) and none of its joints (3-8 angles, 12-17 velocities).
TEST(VaeConfigTest, WalkerRootEncoderConfigReadsNoJoint) {
  const auto c = VaeConfig::load(std::string(VAEGAIL_SOURCE_DIR) + "/configs/walker_vae_root_encoder.json",
                                 VaeConfig::walker());
  EXPECT_EQ(c.encoder_state_indices, (std::vector<int>{0, 1, 2, 9, 10, 11}));
  EXPECT_FALSE(c.action_std_depends_on_state);
  EXPECT_EQ(c.kl_weight, 1.0);
}

TEST(VaeConfigTest, SaveAndLoadFile) {
  const auto path = (std::filesystem::temp_directory_path() /
                     ("vae_config_test_" + std::to_string(::getpid()) + ".json"))
                        .string();
  const auto c = VaeConfig::arm(20, 7);
  c.save(path);
  EXPECT_EQ(VaeConfig::load(path), c);
  std::remove(path.c_str());
  EXPECT_THROW(VaeConfig::load(path), std::runtime_error);
}

}  // namespace
}  // namespace vaegail::vae
