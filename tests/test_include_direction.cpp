// Data flows one way through pfgen's rooms (DESIGN.md, "Rooms and the one direction data flows"):
// no room includes a header of a room above it or beside it on its floor, and an observation
// module does not include another module's headers. This reads every #include "..." of the
// product's sources (support/, runtime/, generator/, python/; not the tests, fuzz targets or
// benchmarks, which stand above everything) and names each one that runs against the direction.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "support/test_paths.hpp"

namespace fs = std::filesystem;

namespace {

// The floors, lowest first. Rooms on one floor do not include each other. The runtime stands
// apart: it includes only itself and support, and of the generator's rooms only the commands
// (cli), where simulate meets it, and those above include it.
const std::map<std::string, int>& floors() {
  static const std::map<std::string, int> floor = {
      {"support", 0},
      {"kinds", 1}, {"algebra", 1},
      {"notation", 2},  // writes algebra's polynomials
      {"model", 3},
      {"derivation", 4},
      {"printing", 5}, {"evaluation", 5}, {"codegen", 5}, {"toolchain", 5},
      {"observations", 6},  // a column of modules, each file serving one room below
      {"runtime", 7},
      {"cli", 8},
      {"api", 9},
      {"python", 10},
  };
  return floor;
}

// Modules whose files include another module's file of the same room: the delayed observation's
// rate is the continuous one's read h back, and a linear h is the continuous observation written
// otherwise, so both share the continuous module's rate terms, reports and code.
const std::set<std::pair<std::string, std::string>>& shared_modules() {
  static const std::set<std::pair<std::string, std::string>> shared = {{"delayed", "continuous"},
                                                                        {"polynomial", "continuous"}};
  return shared;
}

struct Place {
  std::string room;
  std::string module;  // observations/<module>/ only
};

// The room of a file, by its path in the repository; none for a file outside the rooms. A folder
// of generator/src or generator/include/pfgen is a room, placed on a floor above or not.
std::optional<Place> room_of(const std::string& path) {
  static const std::vector<std::pair<std::string, std::string>> prefixes = {
      {"support/", "support"},        {"runtime/", "runtime"}, {"python/", "python"},
      {"generator/api/", "api"},      {"generator/cli/", "cli"},
  };
  for (const auto& [prefix, room] : prefixes)
    if (path.compare(0, prefix.size(), prefix) == 0) return Place{room, {}};
  static const std::regex in_generator(R"(generator/(?:src|include/pfgen)/([a-z_]+)/(?:([a-z_]+)/)?.*)");
  std::smatch match;
  if (!std::regex_match(path, match, in_generator)) return std::nullopt;
  const std::string room = match[1];
  return Place{room, room == "observations" ? std::string(match[2]) : std::string()};
}

// Where an include "NAME" is found: beside the including file, then in the include directories
// the targets give (DESIGN.md's libraries); empty when it is none of the repository's files.
std::string resolve(const fs::path& root, const fs::path& includer, const std::string& name) {
  static const std::vector<std::string> directories = {"generator/include", "generator/api/include",
                                                       "support/include",   "runtime/include",
                                                       "generator/cli"};
  std::vector<fs::path> candidates = {includer.parent_path() / name};
  for (const auto& directory : directories) candidates.push_back(root / directory / name);
  for (const auto& candidate : candidates)
    if (fs::is_regular_file(candidate)) return fs::relative(fs::weakly_canonical(candidate), root).generic_string();
  return {};
}

// Why `from` may not include `to` (empty: it may).
std::string against_direction(const Place& from, const Place& to) {
  if (from.room == to.room) {
    if (from.room != "observations" || from.module == to.module ||
        shared_modules().count({from.module, to.module}))
      return {};
    return "the " + from.module + " module includes the " + to.module + " module";
  }
  const int from_floor = floors().at(from.room), to_floor = floors().at(to.room);
  if (from.room == "runtime") return to.room == "support" ? "" : "the runtime includes the generator's " + to.room;
  if (to.room == "runtime" && from_floor < floors().at("cli"))
    return from.room + " includes the runtime, which only the commands and above meet";
  if (to_floor > from_floor) return from.room + " includes " + to.room + ", a room above it";
  if (to_floor == from_floor) return from.room + " includes " + to.room + ", a room beside it";
  return {};
}

// A room no floor names: its includes, and those of it, would go unchecked.
std::string unplaced(const Place& place) {
  return floors().count(place.room) ? "" : "the room " + place.room + " is on no floor of this test's floors()";
}

std::vector<std::string> includes_against_direction(const fs::path& root) {
  static const std::regex include_line(R"(^\s*#\s*include\s*"([^"]+)\")");
  std::vector<std::string> found;
  for (const char* top : {"support", "runtime", "generator", "python"}) {
    if (!fs::is_directory(root / top)) continue;
    for (const auto& entry : fs::recursive_directory_iterator(root / top)) {
      const std::string extension = entry.path().extension().string();
      if (!entry.is_regular_file() || (extension != ".cpp" && extension != ".hpp" && extension != ".h")) continue;
      const std::string path = fs::relative(entry.path(), root).generic_string();
      const std::optional<Place> from = room_of(path);
      if (!from) continue;
      if (!unplaced(*from).empty()) {
        found.push_back(path + ": " + unplaced(*from));
        continue;
      }
      std::ifstream in(entry.path());
      std::string line;
      for (int number = 1; std::getline(in, line); ++number) {
        std::smatch match;
        if (!std::regex_search(line, match, include_line)) continue;
        const std::string included = resolve(root, entry.path(), match[1]);
        const std::optional<Place> to = included.empty() ? std::nullopt : room_of(included);
        if (!to) continue;
        const std::string why = unplaced(*to).empty() ? against_direction(*from, *to) : unplaced(*to);
        if (!why.empty()) found.push_back(path + ":" + std::to_string(number) + ": " + included + ": " + why);
      }
    }
  }
  return found;
}

}  // namespace

TEST_CASE("No room includes a header of a room above it or beside it", "[unit][design]") {
  const std::vector<std::string> found = includes_against_direction(pfgen_test::source_dir());
  std::string listed;
  for (const auto& line : found) listed += line + "\n";
  INFO(listed);
  CHECK(found.empty());
}

TEST_CASE("The include check sees an include against the direction", "[unit][design]") {
  // The rules themselves, on places a file could have.
  CHECK(against_direction({"derivation", ""}, {"observations", "continuous"}) ==
        "derivation includes observations, a room above it");
  CHECK(against_direction({"observations", "sampled"}, {"cli", ""}) == "observations includes cli, a room above it");
  CHECK(against_direction({"codegen", ""}, {"printing", ""}) == "codegen includes printing, a room beside it");
  CHECK(against_direction({"observations", "sampled"}, {"observations", "delayed"}) ==
        "the sampled module includes the delayed module");
  CHECK(against_direction({"codegen", ""}, {"runtime", ""}) ==
        "codegen includes the runtime, which only the commands and above meet");
  CHECK(against_direction({"runtime", ""}, {"model", ""}) == "the runtime includes the generator's model");
  CHECK(against_direction({"observations", "delayed"}, {"observations", "continuous"}).empty());
  CHECK(against_direction({"cli", ""}, {"runtime", ""}).empty());
  CHECK(against_direction({"printing", ""}, {"derivation", ""}).empty());
  // Files find their rooms by path.
  CHECK(room_of("generator/src/observations/sampled/sampled_code.cpp")->module == "sampled");
  CHECK(room_of("generator/include/pfgen/derivation/filter_equations.hpp")->room == "derivation");
  CHECK(room_of("generator/cli/observations/sampled_command.cpp")->room == "cli");
  CHECK(room_of("generator/api/src/model.cpp")->room == "api");
  CHECK(unplaced(*room_of("generator/src/new_room/part.cpp")) ==
        "the room new_room is on no floor of this test's floors()");
}
