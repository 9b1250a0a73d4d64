#include "pfgen/notation/rich_text.hpp"

#include <stdexcept>

#include "pfgen/notation/latex_printer.hpp"

namespace pfgen {
namespace {

// Walks rich text once: prose characters go to `prose`, each math span's two sides to `math`.
// Malformed markup is a programming error in a built-in string (user text reaches here only
// through rich_text_literal), so it throws std::logic_error rather than print half a formula.
template <class Prose, class Math>
void walk(std::string_view rich, Prose prose, Math math) {
  std::size_t k = 0;
  auto fail = [&](const char* what) {
    throw std::logic_error(std::string("rich text: ") + what + " in \"" + std::string(rich) + "\"");
  };
  while (k < rich.size()) {
    const char c = rich[k];
    if (c == '\\') {
      if (k + 1 == rich.size()) fail("trailing backslash");
      prose(rich[k + 1]);
      k += 2;
    } else if (c == '$') {
      std::string plain;
      ++k;
      for (;; ++k) {
        if (k == rich.size()) fail("math span without '|'");
        if (rich[k] == '\\') {
          if (++k == rich.size()) fail("trailing backslash");
          plain += rich[k];
        } else if (rich[k] == '|') {
          break;
        } else if (rich[k] == '$') {
          fail("math span without '|'");
        } else {
          plain += rich[k];
        }
      }
      const std::size_t end = rich.find('$', ++k);
      if (end == std::string_view::npos) fail("unclosed math span");
      if (plain.empty() || end == k) fail("empty side of a math span");
      math(plain, rich.substr(k, end - k));
      k = end + 1;
    } else {
      prose(c);
      ++k;
    }
  }
}

}  // namespace

std::string rich_text_plain(std::string_view rich) {
  std::string out;
  walk(rich, [&](char c) { out += c; }, [&](const std::string& plain, std::string_view) { out += plain; });
  return out;
}

std::string rich_text_latex(std::string_view rich) {
  std::string out, prose;
  auto flush = [&] {
    out += latex_escape_text(prose);
    prose.clear();
  };
  walk(rich, [&](char c) { prose += c; },
       [&](const std::string&, std::string_view latex) {
         flush();
         out += "$";
         out += latex;
         out += "$";
       });
  flush();
  return out;
}

std::string rich_text_literal(std::string_view text) {
  std::string out;
  for (char c : text) {
    if (c == '\\' || c == '$' || c == '|') out += '\\';
    out += c;
  }
  return out;
}

}  // namespace pfgen
