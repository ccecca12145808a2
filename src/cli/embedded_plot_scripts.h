// The figure scripts of scripts/plot/, compiled in (src/cli/CMakeLists.txt), so the binary draws
// figures without the source tree.
#pragma once

#include <string>

namespace vaegail::cli {

// The text of scripts/plot/`file_name` as it was at build time; throws std::out_of_range for
// a name that is not there.
const std::string& embedded_plot_script(const std::string& file_name);

}  // namespace vaegail::cli
