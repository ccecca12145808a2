// The MJCF files under models/, compiled into the binary so that the default tasks run from
// any working directory. A user's own MJCF file loads from disk through the same wrapper.
#pragma once

#include <string>
#include <vector>

namespace vaegail {

// Throws std::out_of_range naming the file if it is not embedded.
const std::string& embedded_model(const std::string& file_name);
std::vector<std::string> embedded_model_names();

}  // namespace vaegail
