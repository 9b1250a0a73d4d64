#include "plugin_loading.hpp"

#include <filesystem>
#include <iomanip>
#include <iostream>
#include <system_error>

namespace pfgen::cli {

pfgen_runtime::SimulationPlugin load_plugin(const std::string& source, const toolchain::PluginBuildOptions& options,
                                            bool talk, toolchain::PluginBuild& build) {
  build = toolchain::build_plugin(source, options);
  if (talk) {
    if (build.cache_hit)
      std::cerr << "pfgen: plugin " << build.path << " (cached)\n";
    else
      std::cerr << "pfgen: plugin " << build.path << " (compiled in " << std::fixed << std::setprecision(1)
                << build.compile_seconds << " s)\n" << std::defaultfloat;
  }
  try {
    return pfgen_runtime::SimulationPlugin(build.path);
  } catch (const pfgen_runtime::PluginLoadError&) {
    if (!build.cache_hit) throw;
    // A cached plugin that does not load failed every later run until deleted by hand: remove it
    // and build it once more.
    std::error_code ignored;
    std::filesystem::remove(build.path, ignored);
    build = toolchain::build_plugin(source, options);
    if (talk) std::cerr << "pfgen: the cached plugin did not load; rebuilt " << build.path << "\n";
    return pfgen_runtime::SimulationPlugin(build.path);
  }
}

}  // namespace pfgen::cli
