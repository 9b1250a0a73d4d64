#pragma once
// A simulation plugin's source built (a cache hit when another process or an earlier job built
// it) and loaded: what simulate, estimate and fit share.
#include <string>

#include "pfgen/toolchain/plugin_compiler.hpp"
#include "pfgen_runtime/simulation_plugin.hpp"

namespace pfgen::cli {

// `talk`: say on stderr where the plugin is and whether it was compiled. A cached plugin that
// does not load (truncated by a full disk or a killed copy) is removed and built once more.
pfgen_runtime::SimulationPlugin load_plugin(const std::string& source, const toolchain::PluginBuildOptions& options,
                                            bool talk, toolchain::PluginBuild& build);

}  // namespace pfgen::cli
