// Bare-metal start-up for the Cortex-M4F of QEMU's mps2-an386: vector table, reset
// handler (FPU on, .data copied from flash, .bss zeroed, stack painted, static
// constructors run, main called) and a fault handler; all output over semihosting.
// Linked with -nostartfiles: nothing of newlib's crt0 runs.
#include <cstdint>

#include "board.hpp"
#include "semihosting.hpp"

extern "C" {
// From link.ld.
extern std::uint32_t __data_load[], __data_start[], __data_end[];
extern std::uint32_t __bss_start[], __bss_end[];
extern std::uint32_t __stack_limit[], __stack_top[];
extern void (*__init_array_start[])();
extern void (*__init_array_end[])();

int main();
[[noreturn]] void Reset_Handler();
[[noreturn]] void pfgen_embedded_reset_continue();
[[noreturn]] void pfgen_embedded_fault_handler();

// With -nostartfiles nothing provides these; empty ones keep any libc reference satisfied.
void _init() {}
void _fini() {}
}

namespace {

constexpr std::uint32_t stack_paint = 0xA5A5A5A5u;

using Vector = void (*)();

}  // namespace

// Cortex-M vector table: initial stack pointer, then the 15 system exception handlers.
// (No peripheral interrupt is enabled, so no IRQ entries follow.)
extern "C" __attribute__((section(".isr_vector"), used)) const Vector pfgen_embedded_vectors[16] = {
    reinterpret_cast<Vector>(__stack_top),
    Reset_Handler,
    pfgen_embedded_fault_handler,  // NMI
    pfgen_embedded_fault_handler,  // HardFault
    pfgen_embedded_fault_handler,  // MemManage
    pfgen_embedded_fault_handler,  // BusFault
    pfgen_embedded_fault_handler,  // UsageFault (e.g. an FPU instruction with the FPU off)
    nullptr,
    nullptr,
    nullptr,
    nullptr,
    pfgen_embedded_fault_handler,  // SVCall
    pfgen_embedded_fault_handler,  // DebugMonitor
    nullptr,
    pfgen_embedded_fault_handler,  // PendSV
    pfgen_embedded_fault_handler,  // SysTick
};

// The FPU must be on before any compiled code can touch an s-register, so this part is
// assembly: CPACR (0xE000ED88) bits 20-23 give CP10 and CP11 full access.
extern "C" __attribute__((naked, noreturn)) void Reset_Handler() {
  asm volatile(
      "movw r0, #0xED88\n"
      "movt r0, #0xE000\n"
      "ldr r1, [r0]\n"
      "orr r1, r1, #(0xF << 20)\n"
      "str r1, [r0]\n"
      "dsb\n"
      "isb\n"
      "b pfgen_embedded_reset_continue\n");
}

extern "C" [[noreturn]] void pfgen_embedded_reset_continue() {
  for (std::uint32_t *src = __data_load, *dst = __data_start; dst < __data_end;) *dst++ = *src++;
  for (std::uint32_t* dst = __bss_start; dst < __bss_end;) *dst++ = 0;

  // Paint the unused stack below this frame so that main can measure the peak use.
  std::uint32_t* sp;
  asm volatile("mov %0, sp" : "=r"(sp));
  for (volatile std::uint32_t* word = __stack_limit; word < sp - 16;) *word++ = stack_paint;

  for (void (**ctor)() = __init_array_start; ctor < __init_array_end; ++ctor) (*ctor)();
  pfgen_embedded::semihosting::exit(main() == 0);
}

extern "C" [[noreturn]] void pfgen_embedded_fault_handler() {
  pfgen_embedded::semihosting::write("FAULT: exception taken\n");
  pfgen_embedded::semihosting::exit(false);
}

namespace pfgen_embedded::board {

std::uint32_t stack_reserved_bytes() {
  return static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(__stack_top) -
                                    reinterpret_cast<std::uintptr_t>(__stack_limit));
}

std::uint32_t stack_peak_bytes() {
  const volatile std::uint32_t* word = __stack_limit;
  while (word < __stack_top && *word == stack_paint) ++word;
  return static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(__stack_top) -
                                    reinterpret_cast<std::uintptr_t>(word));
}

}  // namespace pfgen_embedded::board
