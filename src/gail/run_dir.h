// What the GAIL and BC run directories share: a config a rerun must agree with, and a
// metrics log cut back to the last checkpoint.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace vaegail {

// Writes `config` to path. If path already holds a config (a resumed run), it must equal
// `config` except on `resumable_keys` (settings that do not change what an iteration
// computes); otherwise std::invalid_argument names the first differing setting.
void check_or_write_config(const std::string& path, const nlohmann::json& config,
                           const std::vector<std::string>& resumable_keys);

// Drops the rows of a metrics CSV whose first column (the iteration or epoch) exceeds
// `last`: rows logged by a run killed before its checkpoint, which the resumed run redoes.
void truncate_metrics(const std::string& path, int last);

}  // namespace vaegail
