// The option checks several subcommands share, and the help texts that list a registry's names,
// so that the help never disagrees with what the options accept.
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "cli_options.hpp"
#include "pfgen/kinds/filter_kinds.hpp"
#include "pfgen_support/quoted_text.hpp"
#include "subcommands.hpp"

namespace pfgen::cli {
namespace {

// A number option's text itself, before CLI11 converts it: strtod turns 1e-9999 into 0 and 1e400
// into infinity, and the message then quoted what the conversion made of it.
std::string check_double_number(std::string& text) {
  errno = 0;
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size()) return pfgen_support::quoted(text) + " is not a number";
  if (errno == ERANGE || !std::isfinite(value))
    return pfgen_support::quoted(text) +
           " is outside the range of a double (magnitudes from about 2.2e-308 to 1.8e308)";
  return std::string();
}

// CLI11 reads unsigned options with strtoull, which takes "-1" as 2^64 - 1 and saturates an
// overflow at 2^64 - 1 without a word (--seed -1 and --seed 18446744073709551616 both ran with
// seed 18446744073709551615; --runs -1 asked for 1.8e19 runs). Only plain digits that fit pass.
std::string check_whole_number(std::string& text) {
  std::uint64_t value = 0;
  const char* end = text.data() + text.size();
  const auto [stop, error] = std::from_chars(text.data(), end, value);
  if (text.empty() || error != std::errc() || stop != end)
    return "'" + text + "' is not a whole number from 0 to 18446744073709551615";
  return std::string();
}

// An empty file name is refused wherever a file is named: simulate and derive used to skip an
// output given as "" without a word, while codegen and latex refused it.
std::string check_named_file(std::string& text) { return text.empty() ? "the file name is empty" : std::string(); }

// An empty filter list is no list: derive --filter "" printed the default filter without a word.
std::string check_named_filters(std::string& text) {
  return text.empty() ? "the list is empty; name filters, or leave the option out for the default" : std::string();
}

}  // namespace

OptionChecks::OptionChecks()
    : double_number(check_double_number, "NUMBER"),
      whole_number(check_whole_number, "UINT"),
      named_file(check_named_file, "FILE"),
      named_filters(check_named_filters, "FILTERS") {}

std::string one_filter_help() { return join(pfgen::filter_kind_names(), " | ") + " | a filter of the model's filters: section"; }

}  // namespace pfgen::cli
