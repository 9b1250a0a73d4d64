// ARM semihosting (bkpt 0xAB on M-profile) for the firmware: QEMU with
// -semihosting-config enable=on,target=native serves these calls on the host.
#pragma once

#include <cstdint>

namespace pfgen_embedded::semihosting {

inline constexpr std::uint32_t sys_write0 = 0x04;  // write a NUL-terminated string to the console
inline constexpr std::uint32_t sys_exit = 0x18;    // stop; QEMU exits 0 on ApplicationExit, else 1
inline constexpr std::uint32_t adp_stopped_application_exit = 0x20026;
inline constexpr std::uint32_t adp_stopped_run_time_error = 0x20023;

inline std::uint32_t call(std::uint32_t operation, const void* argument) {
  register std::uint32_t r0 asm("r0") = operation;
  register const void* r1 asm("r1") = argument;
  asm volatile("bkpt 0xAB" : "+r"(r0) : "r"(r1) : "memory");
  return r0;
}

inline void write(const char* text) { call(sys_write0, text); }

[[noreturn]] inline void exit(bool success) {
  // On AArch32 the SYS_EXIT argument is the reason code itself, not a pointer.
  call(sys_exit, reinterpret_cast<const void*>(success ? adp_stopped_application_exit : adp_stopped_run_time_error));
  for (;;) {
  }
}

}  // namespace pfgen_embedded::semihosting
