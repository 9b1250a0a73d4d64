// Runs the examples of a documentation page and compares what they print with what the page
// shows, so that the README and docs/ stay true (docs/development.md, "Executed documentation").
//
//   doc_examples check  PAGE.md --source DIR --bin DIR --build DIR --work DIR [--long] [--python FILE]
//   doc_examples update PAGE.md --source DIR --bin DIR --build DIR --work DIR [--long] [--python FILE]
//
// --python: the interpreter the Python module was built for (Debian's python3), which the pages'
// `python3` then runs, whatever else is earlier on PATH.
// A page's examples are its fenced code blocks (``` lines):
//   - a block whose info string holds `file=NAME` (```yaml file=model.yaml) is written to NAME in
//     the page's scratch directory before the blocks after it run; with `source=PATH` as well it
//     must equal that repository file (update copies the file into the page);
//   - a block whose first non-empty line starts with "$ " is a session: each "$ " line is a
//     command (a line ending in '\' continues on the next), run by /bin/sh in the scratch
//     directory with the built programs first on PATH, stderr merged into stdout; the lines up to
//     the next command are what it prints;
//   - in what a command prints, a line "..." stands for any number of lines, and "[...]" inside a
//     line for any text: the marks for what varies (timings, paths, dates);
//   - a block preceded by the line <!-- doc-test: long --> runs only with --long (commands that
//     take minutes; `cmake --build build --target check-docs-long`);
//   - a block preceded by the line <!-- doc-test: python --> runs only with --python (it runs the
//     Python module, which a build without it, the sanitizers' for one, does not have).
// A "$ " line outside a fenced block is an error, so no example escapes the test.
// The scratch directory holds links to the source tree's examples/, tests/, scripts/ and docs/,
// and `build` to the build tree (--build), so that pages name paths as a user in the source tree does.
// `update` rewrites the outputs that differ (as `regenerate` does for generated/), keeping "[...]"
// lines that still match; a differing output with a "..." line is left for a person to edit.
#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "pfgen_support/process.hpp"

namespace fs = std::filesystem;

namespace {

struct Command {
  std::size_t first_line = 0;  // index in the page of the "$ " line
  std::size_t output_begin = 0, output_end = 0;  // the page lines shown as its output: [begin, end)
  std::string text;            // the command as sh reads it (continuations joined with newlines)
};

struct Block {
  std::size_t fence_line = 0;
  std::string file_name;          // file=NAME blocks
  std::string source_file;        // source=PATH: the block must equal this repository file
  std::vector<std::string> body;  // the lines between the fences
  std::size_t body_begin = 0;     // page index of body[0]
  bool long_running = false;
  bool needs_python = false;
  std::vector<Command> commands;
};

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::string line;
  std::istringstream in(text);
  while (std::getline(in, line)) lines.push_back(line);
  return lines;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

std::string trim_right(std::string s) {
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.pop_back();
  return s;
}

std::size_t indent_of(const std::string& line) {
  std::size_t k = 0;
  while (k < line.size() && line[k] == ' ') ++k;
  return k;
}

bool is_fence(const std::string& line) { return line.compare(indent_of(line), 3, "```") == 0; }

bool starts_with(const std::string& s, const std::string& prefix) { return s.compare(0, prefix.size(), prefix) == 0; }

// A page's blocks; throws on an unclosed fence or a "$ " line outside any fence.
std::vector<Block> parse_page(const std::string& page_name, const std::vector<std::string>& lines) {
  std::vector<Block> blocks;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string& line = lines[i];
    if (!is_fence(line)) {
      const std::size_t k = indent_of(line);
      if (line.compare(k, 2, "$ ") == 0)
        throw std::runtime_error(page_name + ":" + std::to_string(i + 1) +
                                 ": a command example outside a fenced block (put it between ``` lines)");
      continue;
    }
    Block block;
    block.fence_line = i;
    const std::size_t indent = indent_of(line);
    const std::string info = line.substr(indent + 3);
    const auto file_at = info.find("file=");
    if (file_at != std::string::npos) {
      block.file_name = info.substr(file_at + 5);
      block.file_name = block.file_name.substr(0, block.file_name.find(' '));
      if (block.file_name.empty() || block.file_name.find('/') != std::string::npos || block.file_name[0] == '.')
        throw std::runtime_error(page_name + ":" + std::to_string(i + 1) + ": file= needs a plain file name");
    }
    const auto source_at = info.find("source=");
    if (source_at != std::string::npos) {
      block.source_file = info.substr(source_at + 7);
      block.source_file = block.source_file.substr(0, block.source_file.find(' '));
    }
    for (std::size_t back = i; back-- > 0;) {
      const std::string previous = trim_right(lines[back]);
      if (previous.empty()) continue;
      block.long_running = previous.find("<!-- doc-test: long -->") != std::string::npos;
      block.needs_python = previous.find("<!-- doc-test: python -->") != std::string::npos;
      break;
    }
    std::size_t j = i + 1;
    for (; j < lines.size() && !is_fence(lines[j]); ++j) {
      // Lines of a block inside a list item carry the item's indentation.
      const std::string& body_line = lines[j];
      block.body.push_back(indent_of(body_line) >= indent ? body_line.substr(indent) : body_line);
    }
    if (j == lines.size())
      throw std::runtime_error(page_name + ":" + std::to_string(i + 1) + ": a code block that is never closed");
    block.body_begin = i + 1;
    std::size_t first = 0;
    while (first < block.body.size() && trim_right(block.body[first]).empty()) ++first;
    if (block.file_name.empty() && first < block.body.size() && starts_with(block.body[first], "$ ")) {
      for (std::size_t b = first; b < block.body.size();) {
        if (!starts_with(block.body[b], "$ ")) {
          ++b;
          continue;
        }
        Command command;
        command.first_line = block.body_begin + b;
        command.text = block.body[b].substr(2);
        while (!command.text.empty() && command.text.back() == '\\' && b + 1 < block.body.size()) {
          ++b;
          command.text += "\n" + block.body[b];
        }
        ++b;
        command.output_begin = block.body_begin + b;
        while (b < block.body.size() && !starts_with(block.body[b], "$ ")) ++b;
        command.output_end = block.body_begin + b;
        block.commands.push_back(command);
      }
    }
    blocks.push_back(block);
    i = j;
  }
  return blocks;
}

// "[...]" in a pattern line matches any text.
bool line_matches(const std::string& pattern, const std::string& text) {
  const std::string mark = "[...]";
  std::size_t at = pattern.find(mark);
  if (at == std::string::npos) return pattern == text;
  const std::string head = pattern.substr(0, at);
  if (!starts_with(text, head)) return false;
  std::string rest_pattern = pattern.substr(at + mark.size());
  for (std::size_t k = head.size(); k <= text.size(); ++k)
    if (line_matches(rest_pattern, text.substr(k))) return true;
  return false;
}

// The expected lines against the printed ones; a "..." line matches any run of lines.
bool lines_match(const std::vector<std::string>& expected, std::size_t e, const std::vector<std::string>& actual,
                 std::size_t a) {
  if (e == expected.size()) return a == actual.size();
  if (expected[e] == "...") {
    for (std::size_t k = a; k <= actual.size(); ++k)
      if (lines_match(expected, e + 1, actual, k)) return true;
    return false;
  }
  return a < actual.size() && line_matches(expected[e], actual[a]) && lines_match(expected, e + 1, actual, a + 1);
}

std::vector<std::string> without_trailing_blank(std::vector<std::string> lines) {
  for (auto& line : lines) line = trim_right(line);
  while (!lines.empty() && lines.back().empty()) lines.pop_back();
  return lines;
}

std::string page_slug(const std::string& page) {
  std::string slug;
  for (char c : page) slug += (std::isalnum(static_cast<unsigned char>(c)) ? c : '_');
  return slug;
}

struct Options {
  bool update = false, long_running = false;
  fs::path source, bin, build, work, python;
  std::vector<std::string> pages;
};

Options parse_options(int argc, char** argv) {
  Options options;
  if (argc < 2) throw std::runtime_error("usage: doc_examples check|update PAGE.md... --source DIR --bin DIR --build DIR --work DIR [--long]");
  const std::string mode = argv[1];
  if (mode != "check" && mode != "update") throw std::runtime_error("the first argument must be check or update");
  options.update = mode == "update";
  for (int k = 2; k < argc; ++k) {
    const std::string arg = argv[k];
    auto value = [&]() -> std::string {
      if (k + 1 >= argc) throw std::runtime_error(arg + " needs a value");
      return argv[++k];
    };
    if (arg == "--source") options.source = value();
    else if (arg == "--bin") options.bin = value();
    else if (arg == "--work") options.work = value();
    else if (arg == "--build") options.build = value();
    else if (arg == "--python") options.python = value();
    else if (arg == "--long") options.long_running = true;
    else options.pages.push_back(arg);
  }
  if (options.source.empty() || options.bin.empty() || options.work.empty() || options.pages.empty())
    throw std::runtime_error("--source, --bin, --work and at least one page are needed");
  // The scratch directories' links and PATH must not depend on where the runner was started.
  options.source = fs::absolute(options.source);
  options.bin = fs::absolute(options.bin);
  options.work = fs::absolute(options.work);
  if (!options.build.empty()) options.build = fs::absolute(options.build);
  return options;
}

// Runs one page; returns the number of examples that differ (after rewriting them with update).
int run_page(const Options& options, const std::string& page) {
  const fs::path page_path = options.source / page;
  std::vector<std::string> lines = split_lines(read_text(page_path));
  const std::vector<Block> blocks = parse_page(page, lines);
  const fs::path scratch = options.work / page_slug(page);
  fs::remove_all(scratch);
  fs::create_directories(scratch);
  for (const char* shared : {"examples", "tests", "scripts", "docs", "benchmarks"})
    fs::create_directory_symlink(options.source / shared, scratch / shared);
  if (!options.build.empty()) fs::create_directory_symlink(fs::absolute(options.build), scratch / "build");

  struct Rewrite {
    std::size_t begin, end;
    std::vector<std::string> lines;
  };
  std::vector<Rewrite> rewrites;
  int differing = 0, run = 0;
  for (const Block& block : blocks) {
    if (block.long_running && !options.long_running) continue;
    if (block.needs_python && options.python.empty()) continue;
    if (!block.file_name.empty()) {
      std::vector<std::string> body = block.body;
      if (!block.source_file.empty()) {
        // One home: the page shows the repository's file, and the test keeps the two equal.
        const std::vector<std::string> source = split_lines(read_text(options.source / block.source_file));
        if (without_trailing_blank(source) != without_trailing_blank(body)) {
          ++differing;
          std::cerr << page << ":" << block.fence_line + 1 << ": the block differs from " << block.source_file << "\n";
          if (options.update) {
            const std::string indent(indent_of(lines[block.fence_line]), ' ');
            Rewrite rewrite{block.body_begin, block.body_begin + block.body.size(), {}};
            for (const auto& line : source) rewrite.lines.push_back(line.empty() ? line : indent + line);
            rewrites.push_back(rewrite);
          }
        }
        body = source;
      }
      std::ofstream out(scratch / block.file_name, std::ios::binary);
      for (const auto& line : body) out << line << "\n";
      if (!out) throw std::runtime_error("cannot write " + (scratch / block.file_name).string());
      continue;
    }
    for (const Command& command : block.commands) {
      ++run;
      const std::string script = "cd '" + scratch.string() + "' && " + command.text;
      const auto result = pfgen_support::run_program({"timeout", "1800", "sh", "-c", script});
      const std::vector<std::string> actual = without_trailing_blank(split_lines(result.output));
      std::vector<std::string> expected;
      for (std::size_t k = command.output_begin; k < command.output_end; ++k) {
        const std::size_t indent = indent_of(lines[block.fence_line]);
        expected.push_back(indent_of(lines[k]) >= indent ? lines[k].substr(indent) : lines[k]);
      }
      expected = without_trailing_blank(expected);
      if (lines_match(expected, 0, actual, 0)) continue;
      ++differing;
      std::cerr << page << ":" << command.first_line + 1 << ": `" << command.text << "` (exit status "
                << result.exit_status << ") printed what the page does not show:\n";
      for (const auto& line : actual) std::cerr << "  | " << line << "\n";
      if (!options.update) continue;
      bool has_gap = false;
      for (const auto& line : expected) has_gap = has_gap || line == "...";
      if (has_gap) {
        std::cerr << page << ":" << command.first_line + 1 << ": not rewritten: its output has a \"...\" line; edit it by hand\n";
        continue;
      }
      Rewrite rewrite{command.output_begin, command.output_end, {}};
      const std::string indent(indent_of(lines[block.fence_line]), ' ');
      for (const auto& line : actual) {
        std::string kept = line;
        for (const auto& pattern : expected)
          if (pattern.find("[...]") != std::string::npos && line_matches(pattern, line)) kept = pattern;
        rewrite.lines.push_back(kept.empty() ? kept : indent + kept);
      }
      rewrites.push_back(rewrite);
    }
  }
  if (!rewrites.empty()) {
    std::sort(rewrites.begin(), rewrites.end(), [](const Rewrite& a, const Rewrite& b) { return a.begin < b.begin; });
    for (auto it = rewrites.rbegin(); it != rewrites.rend(); ++it) {
      lines.erase(lines.begin() + static_cast<std::ptrdiff_t>(it->begin), lines.begin() + static_cast<std::ptrdiff_t>(it->end));
      lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(it->begin), it->lines.begin(), it->lines.end());
    }
    std::ofstream out(page_path, std::ios::binary);
    for (const auto& line : lines) out << line << "\n";
    std::cerr << page << ": rewrote " << rewrites.size() << " example output(s); review with git diff\n";
  }
  std::cout << page << ": " << run << " command(s), " << differing << " differing\n";
  // update fails only for what it could not rewrite.
  return differing - static_cast<int>(rewrites.size());
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options options = parse_options(argc, argv);
    const char* path = std::getenv("PATH");
    std::string search = fs::absolute(options.bin).string() + ":" + (path ? path : "/usr/bin:/bin");
    if (!options.python.empty()) {  // `python3` on the pages is the module's interpreter
      const fs::path python_bin = options.work / "python-bin";
      fs::create_directories(python_bin);
      // Pages run in parallel share this directory: the link is made under a name of this process's
      // own and renamed into place, which replaces atomically (remove-then-create raced: "File exists").
      const fs::path own = python_bin / ("python3." + std::to_string(getpid()));
      fs::remove(own);
      fs::create_symlink(fs::absolute(options.python), own);
      fs::rename(own, python_bin / "python3");
      search = python_bin.string() + ":" + search;
    }
    setenv("PATH", search.c_str(), 1);
    setenv("PFGEN_SOURCE_DIR", fs::absolute(options.source).c_str(), 1);
    int differing = 0;
    for (const auto& page : options.pages) {
      try {
        differing += run_page(options, page);
      } catch (const std::exception& e) {  // a malformed page: say so, and go on with the others
        std::cerr << "doc_examples: " << e.what() << "\n";
        ++differing;
      }
    }
    return differing == 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "doc_examples: " << e.what() << "\n";
    return 2;
  }
}
