#include "pfgen/toolchain/plugin_compiler.hpp"

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <system_error>

#include "pfgen_support/content_hash.hpp"
#include "pfgen_support/atomic_file.hpp"

namespace pfgen::toolchain {
namespace {

namespace fs = std::filesystem;

std::string environment(const char* name) {
  const char* value = std::getenv(name);
  return value ? value : "";
}

std::vector<std::string> split_words(const std::string& text) {
  std::vector<std::string> words;
  std::istringstream in(text);
  for (std::string word; in >> word;) words.push_back(word);
  return words;
}

std::string first_line(const std::string& text) { return text.substr(0, text.find('\n')); }

// The compiler's identity, asked once per command and process: a hit then runs no program at
// all, and a compiler upgraded between two pfgen runs still gets a new key.
std::string compiler_identity(const std::vector<std::string>& compiler) {
  static std::mutex mutex;
  static std::map<std::vector<std::string>, std::string> known;
  std::lock_guard<std::mutex> lock(mutex);
  auto it = known.find(compiler);
  if (it != known.end()) return it->second;
  std::vector<std::string> argv = compiler;
  argv.push_back("--version");
  const std::string name = command_line(compiler);
  ProcessResult result;
  try {
    result = run_program(argv);
  } catch (const ToolchainError& e) {
    throw ToolchainError("cannot run the C++ compiler `" + name + "` (" + e.what() +
                         "); set CXX to a working C++ compiler");
  }
  if (!result.succeeded())
    throw ToolchainError("the C++ compiler `" + name + "` failed on --version (" +
                         (result.signal ? "signal " + std::to_string(result.signal)
                                        : "exit status " + std::to_string(result.exit_status)) +
                         "); set CXX to a working C++ compiler");
  return known[compiler] = first_line(result.output);
}

std::vector<std::string> compiler_words(const PluginBuildOptions& options) {
  std::vector<std::string> words = split_words(options.compiler.empty() ? default_compiler() : options.compiler);
  if (words.empty()) throw ToolchainError("the C++ compiler command is empty");
  return words;
}

std::vector<std::string> flags_of(const PluginBuildOptions& options) {
  return options.flags.empty() ? default_plugin_flags() : options.flags;
}

std::string key_of(const std::string& source, const std::vector<std::string>& compiler,
                   const std::vector<std::string>& flags) {
  pfgen_support::ContentHash hash;
  hash.add("pfgen " PFGEN_VERSION).add(command_line(compiler)).add(compiler_identity(compiler));
  hash.add(std::to_string(flags.size()));
  for (const auto& flag : flags) hash.add(flag);
  return hash.add(source).hex();
}

bool read_file(const fs::path& path, std::string& text) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::ostringstream s;
  s << in.rdbuf();
  text = s.str();
  return true;
}

// Writes through the support library's unique temporary and rename(), so that concurrent
// processes filling the same cache entry never see a partial file.
void write_atomically(const fs::path& path, const std::string& text) {
  try {
    pfgen_support::write_file_atomically(path.string(), text);
  } catch (const pfgen_support::AtomicWriteError& e) {
    throw ToolchainError("cannot write " +
                         (e.stage() == pfgen_support::AtomicWriteError::Stage::write ? e.temporary() : path.string()));
  }
}

// The compiler's output from its first error on (what a user needs), a dozen lines at most.
std::string error_excerpt(const std::string& output) {
  std::vector<std::string> lines;
  std::istringstream in(output);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  std::size_t start = 0;
  for (std::size_t k = 0; k < lines.size(); ++k)
    if (lines[k].find("error") != std::string::npos) {
      start = k;
      break;
    }
  std::string out;
  for (std::size_t k = start; k < lines.size() && k < start + 12; ++k) out += "  " + lines[k] + "\n";
  return out;
}

}  // namespace

std::string default_compiler() {
  const std::string cxx = environment("CXX");
  return cxx.empty() ? "c++" : cxx;
}

std::vector<std::string> default_plugin_flags() {
  return {"-O2", "-std=c++17", "-fPIC", "-shared", "-fvisibility=hidden", "-ffp-contract=off"};
}

std::string default_cache_dir() {
  if (const std::string dir = environment("PFGEN_CACHE_DIR"); !dir.empty()) return dir;
  if (const std::string xdg = environment("XDG_CACHE_HOME"); !xdg.empty()) return xdg + "/pfgen";
  if (const std::string home = environment("HOME"); !home.empty()) return home + "/.cache/pfgen";
  throw ToolchainError("no cache directory: set PFGEN_CACHE_DIR (or XDG_CACHE_HOME or HOME)");
}

std::string plugin_cache_key(const std::string& source, const PluginBuildOptions& options) {
  return key_of(source, compiler_words(options), flags_of(options));
}

PluginBuild build_plugin(const std::string& source, const PluginBuildOptions& options) {
  const std::vector<std::string> compiler = compiler_words(options);
  const std::vector<std::string> flags = flags_of(options);
  PluginBuild build;
  build.key = key_of(source, compiler, flags);  // runs the compiler's --version: fails before any file is written

  const fs::path dir = fs::absolute(options.cache_dir.empty() ? default_cache_dir() : options.cache_dir) / build.key;
  const fs::path library = dir / "plugin.so", source_path = dir / "plugin.cpp", log = dir / "build.log";
  build.path = library.string();
  build.log_path = log.string();

  std::string stored;
  if (fs::is_regular_file(library) && read_file(source_path, stored) && stored == source) {
    build.cache_hit = true;
    return build;
  }

  std::error_code error;
  fs::create_directories(dir, error);
  if (error) throw ToolchainError("cannot create the plugin cache directory " + dir.string() + ": " + error.message());
  write_atomically(source_path, source);

  const fs::path temporary = pfgen_support::unique_temporary_path(library.string());
  std::vector<std::string> argv = compiler;
  argv.insert(argv.end(), flags.begin(), flags.end());
  argv.insert(argv.end(), {"-o", temporary.string(), source_path.string()});
  if (options.before_compile) options.before_compile(command_line(argv));
  const auto start = std::chrono::steady_clock::now();
  ProcessResult result;
  try {
    result = run_program(argv);
  } catch (const ToolchainError& e) {
    throw ToolchainError("cannot run the C++ compiler `" + command_line(compiler) + "` (" + e.what() + ")");
  }
  build.compile_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::string status =
      result.signal ? "signal " + std::to_string(result.signal) : "exit status " + std::to_string(result.exit_status);
  write_atomically(log, "$ " + command_line(argv) + "\n" + result.output + "[" + status + "]\n");

  if (!result.succeeded() || !fs::is_regular_file(temporary)) {
    fs::remove(temporary, error);
    const std::string what = result.succeeded() ? "wrote no shared object" : "failed (" + status + ")";
    throw PluginCompileError("compiling the simulation plugin with `" + command_line(compiler) + "` " + what + ":\n" +
                                 error_excerpt(result.output) + "full log: " + log.string(),
                             log.string());
  }
  fs::rename(temporary, library, error);
  if (error) {
    const std::string reason = error.message();
    fs::remove(temporary, error);
    throw ToolchainError("cannot move the compiled plugin into place at " + library.string() + ": " + reason);
  }
  return build;
}

}  // namespace pfgen::toolchain
