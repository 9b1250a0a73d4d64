#include "pfgen/printing/json_writer.hpp"

#include <cmath>
#include <cstdio>
#include <ostream>
#include <stdexcept>

#include "pfgen/notation/number_format.hpp"

namespace pfgen {

namespace {

// The length of the well-formed UTF-8 sequence starting at text[k] (a byte >= 0x80), or 0 when it
// is not one (a stray continuation byte, a truncated, overlong or surrogate sequence, or above U+10FFFF).
std::size_t utf8_sequence(const std::string& text, std::size_t k) {
  const auto byte = [&](std::size_t i) { return i < text.size() ? static_cast<unsigned char>(text[i]) : 0u; };
  const unsigned c = byte(k);
  // The sequence's length and its second byte's range (RFC 3629's table).
  std::size_t length = 0;
  unsigned low = 0x80, high = 0xBF;
  if (c >= 0xC2 && c <= 0xDF) {
    length = 2;
  } else if (c >= 0xE0 && c <= 0xEF) {
    length = 3;
    if (c == 0xE0) low = 0xA0;   // no overlong forms
    if (c == 0xED) high = 0x9F;  // no surrogates
  } else if (c >= 0xF0 && c <= 0xF4) {
    length = 4;
    if (c == 0xF0) low = 0x90;   // no overlong forms
    if (c == 0xF4) high = 0x8F;  // nothing above U+10FFFF
  } else {
    return 0;
  }
  if (byte(k + 1) < low || byte(k + 1) > high) return 0;
  for (std::size_t i = 2; i < length; ++i)
    if (byte(k + i) < 0x80 || byte(k + i) > 0xBF) return 0;
  return length;
}

}  // namespace

std::string json_quote(const std::string& text) {
  std::string out;
  out.reserve(text.size() + 2);
  out += '"';
  // Runs of characters that need no escape are appended whole: reports quote megabytes.
  std::size_t plain_from = 0;
  for (std::size_t k = 0; k < text.size(); ++k) {
    const unsigned char c = static_cast<unsigned char>(text[k]);
    if (c >= 0x80) {
      // JSON is UTF-8: a byte that is not (a file's path may hold any) becomes U+FFFD.
      if (const std::size_t length = utf8_sequence(text, k)) {
        k += length - 1;
        continue;
      }
      out.append(text, plain_from, k - plain_from);
      plain_from = k + 1;
      out += "\\ufffd";
      continue;
    }
    if (c >= 0x20 && c != '"' && c != '\\') continue;
    out.append(text, plain_from, k - plain_from);
    plain_from = k + 1;
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      case '\r': out += "\\r"; break;
      default: {
        char buffer[8];
        std::snprintf(buffer, sizeof buffer, "\\u%04x", c);
        out += buffer;
      }
    }
  }
  out.append(text, plain_from, std::string::npos);
  out += '"';
  return out;
}

Json Json::string(std::string value) {
  Json j;
  j.kind_ = Kind::String;
  j.scalar_ = std::make_shared<const std::string>(json_quote(value));
  return j;
}

Json Json::number(double value) {
  if (!std::isfinite(value)) throw std::domain_error("result is not a finite number");
  Json j;
  j.kind_ = Kind::Number;
  j.scalar_ = std::make_shared<const std::string>(shortest_double(value));
  return j;
}

Json Json::integer(std::uint64_t value) {
  Json j;
  j.kind_ = Kind::Number;
  j.scalar_ = std::make_shared<const std::string>(std::to_string(value));
  return j;
}

Json Json::boolean(bool value) {
  Json j;
  j.kind_ = Kind::Boolean;
  j.scalar_ = std::make_shared<const std::string>(value ? "true" : "false");
  return j;
}

Json Json::array(std::vector<Json> items) {
  Json j;
  j.kind_ = Kind::Array;
  j.items_ = std::move(items);
  return j;
}

Json Json::object() { return Json(); }

Json& Json::add(const std::string& key, Json value) {
  if (kind_ != Kind::Object) throw std::logic_error("Json::add on a non-object");
  keys_.push_back(key);
  items_.push_back(std::move(value));
  return *this;
}

Json& Json::push(Json value) {
  if (kind_ != Kind::Array) throw std::logic_error("Json::push on a non-array");
  items_.push_back(std::move(value));
  return *this;
}

bool Json::is_scalar_array() const {
  for (const auto& item : items_)
    if (item.kind_ == Kind::Array || item.kind_ == Kind::Object) return false;
  return true;
}

namespace {
void drain(std::string& out, std::ostream* sink) {
  if (sink == nullptr || out.size() < (1u << 20)) return;
  sink->write(out.data(), static_cast<std::streamsize>(out.size()));
  out.clear();
}
}  // namespace

void Json::write(std::string& out, int indent, std::ostream* sink) const {
  const std::string pad(indent + 2, ' ');
  switch (kind_) {
    case Kind::String:
    case Kind::Number:
    case Kind::Boolean:
      out += *scalar_;
      return;
    case Kind::Array: {
      if (is_scalar_array() || indent < 0) {
        out += "[";
        for (std::size_t k = 0; k < items_.size(); ++k) {
          if (k) out += ", ";
          items_[k].write(out, indent, sink);
          drain(out, sink);
        }
        out += "]";
        return;
      }
      out += "[\n";
      for (std::size_t k = 0; k < items_.size(); ++k) {
        out += pad;
        items_[k].write(out, indent + 2, sink);
        out += k + 1 < items_.size() ? ",\n" : "\n";
        drain(out, sink);
      }
      out += std::string(indent, ' ') + "]";
      return;
    }
    case Kind::Object: {
      if (items_.empty()) {
        out += "{}";
        return;
      }
      if (indent < 0) {
        out += "{";
        for (std::size_t k = 0; k < items_.size(); ++k) {
          out += (k ? ", " : "") + json_quote(keys_[k]) + ": ";
          items_[k].write(out, -1);
        }
        out += "}";
        return;
      }
      out += "{\n";
      for (std::size_t k = 0; k < items_.size(); ++k) {
        out += pad + json_quote(keys_[k]) + ": ";
        items_[k].write(out, indent + 2, sink);
        out += k + 1 < items_.size() ? ",\n" : "\n";
        drain(out, sink);
      }
      out += std::string(indent, ' ') + "}";
      return;
    }
  }
}

std::string Json::dump_line() const {
  std::string out;
  write(out, -1);
  return out + "\n";
}

std::string Json::dump() const {
  std::string out;
  write(out, 0);
  return out + "\n";
}

void Json::dump(std::ostream& sink) const {
  std::string out;
  write(out, 0, &sink);
  out += "\n";
  sink.write(out.data(), static_cast<std::streamsize>(out.size()));
}

}  // namespace pfgen
