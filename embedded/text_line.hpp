// A fixed-size line of text with a small number formatter, shared by the firmware and
// the host run so that both print the trajectory in exactly the same format.
//
// No stdio: newlib's printf family links malloc and _sbrk (its buffering and dtoa
// allocate), and the firmware must not link any heap symbol. Numbers are written as
// d.dddddddde+XX, nine significant digits, enough to round-trip any float. The
// conversion runs in double arithmetic (software on Cortex-M4F), which keeps the
// formatter's own error near 1e-15 relative, far below the float tolerance checked.
#pragma once

#include <cstddef>
#include <cstdint>

namespace pfgen_embedded {

class Line {
 public:
  Line() { buffer_[0] = '\0'; }

  const char* c_str() const { return buffer_; }

  void text(const char* s) {
    while (*s != '\0') put(*s++);
  }

  void integer(long value) {
    if (value < 0) {
      put('-');
      value = -value;
    }
    char digits[24];
    int count = 0;
    do {
      digits[count++] = static_cast<char>('0' + value % 10);
      value /= 10;
    } while (value != 0);
    while (count > 0) put(digits[--count]);
  }

  // Nine significant digits in scientific notation; "nan", "inf", "-inf" otherwise.
  void number(double value) {
    if (value != value) {
      text("nan");
      return;
    }
    if (value < 0) {
      put('-');
      value = -value;
    }
    if (value > 1.7976931348623157e308) {
      text("inf");
      return;
    }
    int exponent = 0;
    std::uint64_t digits = 0;
    if (value != 0) {
      // Bring value into [1, 10): at most a few hundred steps, each exact to half an ulp.
      while (value >= 1e16) { value /= 1e16; exponent += 16; }
      while (value >= 10.0) { value /= 10.0; ++exponent; }
      while (value < 1e-16) { value *= 1e16; exponent -= 16; }
      while (value < 1.0) { value *= 10.0; --exponent; }
      digits = static_cast<std::uint64_t>(value * 1e8 + 0.5);
      if (digits >= 1000000000u) {  // 9.999999996 rounds up to 10.0000000
        digits /= 10;
        ++exponent;
      }
    }
    char mantissa[9];
    for (int i = 8; i >= 0; --i) {
      mantissa[i] = static_cast<char>('0' + digits % 10);
      digits /= 10;
    }
    put(mantissa[0]);
    put('.');
    for (int i = 1; i < 9; ++i) put(mantissa[i]);
    put('e');
    put(exponent < 0 ? '-' : '+');
    if (exponent < 0) exponent = -exponent;
    if (exponent >= 100) put(static_cast<char>('0' + exponent / 100));
    put(static_cast<char>('0' + exponent / 10 % 10));
    put(static_cast<char>('0' + exponent % 10));
  }

 private:
  void put(char c) {
    if (length_ + 1 < sizeof buffer_) {
      buffer_[length_++] = c;
      buffer_[length_] = '\0';
    }
  }

  char buffer_[256];
  std::size_t length_ = 0;
};

}  // namespace pfgen_embedded
