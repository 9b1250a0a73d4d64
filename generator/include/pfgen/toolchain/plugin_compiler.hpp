#pragma once
// Compiles a simulation plugin's source (codegen/simulation_plugin.hpp) into a shared object
// with the system's C++ compiler, through a cache so that the second `pfgen simulate` of the
// same model starts at once.
//
// Cache layout: <cache_dir>/<key>/plugin.so, plugin.cpp (the source), build.log (the command
// and the compiler's output). The key is a 64-bit FNV-1a hash (pfgen_support/content_hash.hpp) of the pfgen
// version, the compiler command, the first line of its `--version`, the flags and the whole
// source (which contains the ABI header, and so its version). An entry counts only when its
// plugin.cpp equals the source byte for byte, so a hash collision costs a rebuild, never a
// wrong plugin. The shared object is built under a temporary name in the entry's directory and
// renamed into place, so concurrent pfgen processes never see, or load, a partial file.
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "pfgen/toolchain/process.hpp"

namespace pfgen::toolchain {

// The compiler ran and failed: the message quotes the first lines of its output and names the
// full log.
class PluginCompileError : public ToolchainError {
 public:
  PluginCompileError(const std::string& message, std::string log_path)
      : ToolchainError(message), log_path_(std::move(log_path)) {}
  const std::string& log_path() const { return log_path_; }

 private:
  std::string log_path_;
};

struct PluginBuildOptions {
  // The compiler command, split at spaces ("ccache g++" works, quoting does not).
  // Empty: default_compiler().
  std::string compiler;
  // Empty: default_plugin_flags().
  std::vector<std::string> flags;
  // Empty: default_cache_dir().
  std::string cache_dir;
  // Called on a cache miss, just before the compiler runs, with its command line: a compile can
  // take a minute for a large model, and the caller says so rather than wait in silence.
  std::function<void(const std::string& command)> before_compile;
};

struct PluginBuild {
  std::string path;      // <cache_dir>/<key>/plugin.so, ready for dlopen
  std::string key;       // 16 hex digits
  std::string log_path;  // <cache_dir>/<key>/build.log (on a hit: from the build that made the entry)
  bool cache_hit = false;
  double compile_seconds = 0;  // wall time of the compiler run; 0 on a hit
};

// $CXX when set and not empty, else "c++".
std::string default_compiler();
// -O2 -std=c++17 -fPIC -shared -fvisibility=hidden -ffp-contract=off: no -march=native and no
// -ffast-math, and no contraction into fused multiply-adds (which some targets do by default),
// so that results are the same on every machine of an architecture.
std::vector<std::string> default_plugin_flags();
// $PFGEN_CACHE_DIR, else $XDG_CACHE_HOME/pfgen, else $HOME/.cache/pfgen (ToolchainError if
// none of them is set).
std::string default_cache_dir();

// The cache key of `source` under `options`. Runs the compiler's --version once per compiler
// command and process (ToolchainError if it cannot be run or fails).
std::string plugin_cache_key(const std::string& source, const PluginBuildOptions& options = {});

// Returns the cached shared object for `source`, compiling it first on a miss. Throws
// ToolchainError when the compiler cannot be run (nothing is written to the cache then), or
// PluginCompileError when it fails (the entry keeps plugin.cpp and build.log, no plugin.so).
PluginBuild build_plugin(const std::string& source, const PluginBuildOptions& options = {});

}  // namespace pfgen::toolchain
