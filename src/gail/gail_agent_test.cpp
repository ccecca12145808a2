#include "gail/gail_agent.h"

#include <gtest/gtest.h>

#include <string>

#include "gail/bc_agent.h"
#include "util/atomic_file.h"

namespace vaegail {
namespace {

using nlohmann::json;

json committed_config(const std::string& run) {
  return json::parse(read_file(std::string(VAEGAIL_SOURCE_DIR) + "/checkpoints/walker/" + run + "/config.json"));
}

// Every key of a committed config.json reads back as it was written: a resumed run compares its
// config with the stored one.
template <class Options>
void expect_reads_back(const json& stored) {
  const json reread = stored.get<Options>();
  for (const auto& [key, value] : stored.items()) EXPECT_EQ(reread.at(key), value) << key;
}

TEST(GailOptions, CommittedConfigsReadBackUnchanged) {
  for (const std::string run : {"diverse_gail", "diverse_gail_fast", "plain_gail"}) {
    SCOPED_TRACE(run);
    expect_reads_back<GailOptions>(committed_config(run));
  }
  // These two files have every key there is: the options write exactly those.
  EXPECT_EQ(json(committed_config("diverse_gail_fast").get<GailOptions>()), committed_config("diverse_gail_fast"));
  EXPECT_EQ(json(committed_config("bc").get<BcOptions>()), committed_config("bc"));
}

TEST(GailOptions, RoundTripsEveryField) {
  GailOptions o;
  o.mode = GailMode::Plain;
  o.iterations = 7;
  o.policy_hidden = {3};
  o.discriminator_state_indices = {1, 2};
  o.discriminator_minibatches = 4;
  o.seed = 1ull << 40;
  o.vae_path = "v.pt";
  const json j = o;
  EXPECT_EQ(j.at("mode"), "plain");
  EXPECT_EQ(json(j.get<GailOptions>()), j);
}

TEST(GailOptions, MissingKeysTakeTheDefaultsExceptTheOldFullBatch) {
  const GailOptions defaults;
  const GailOptions read = json::object().get<GailOptions>();
  EXPECT_EQ(read.mode, GailMode::Diverse);
  EXPECT_EQ(read.iterations, defaults.iterations);
  EXPECT_EQ(read.discriminator_hidden, defaults.discriminator_hidden);
  // Runs made before the option trained every discriminator step on the whole batch.
  EXPECT_EQ(defaults.discriminator_minibatches, 10);
  EXPECT_EQ(read.discriminator_minibatches, 1);
  EXPECT_EQ(committed_config("diverse_gail").get<GailOptions>().discriminator_minibatches, 1);
  EXPECT_EQ(json({{"discriminator_minibatches", 10}}).get<GailOptions>().discriminator_minibatches, 10);
}

TEST(GailOptions, AnUnknownModeThrowsNamingIt) {
  try {
    json({{"mode", "fancy"}}).get<GailOptions>();
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "GAIL mode must be diverse or plain, not 'fancy'");
  }
  EXPECT_THROW(json({{"mode", 1}}).get<GailOptions>(), json::type_error);
}

TEST(BcOptions, MissingKeysTakeTheDefaults) {
  const BcOptions read = json({{"epochs", 3}}).get<BcOptions>(), defaults;
  EXPECT_EQ(read.epochs, 3);
  EXPECT_EQ(read.hidden, defaults.hidden);
  EXPECT_EQ(read.batch_size, defaults.batch_size);
}

}  // namespace
}  // namespace vaegail
