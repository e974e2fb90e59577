// SPDX-License-Identifier: MIT
/* Minimal Cortex-M startup: vector table (stack pointer + reset), .data copy, .bss zeroing, static
   constructors, main. Enough to link and size the program; a board port brings its own (CMSIS). */
#include <stdint.h>

extern uint32_t _sidata, _sdata, _edata, _sbss, _ebss, _estack;
extern void __libc_init_array(void);
extern int main(void);

void Reset_Handler(void);
void Default_Handler(void);

void Reset_Handler(void) {
    /* FPU on: CPACR CP10/CP11 full access (the compiler emits VFP instructions). */
    *(volatile uint32_t*)0xE000ED88u |= (0xFu << 20);
    __asm volatile("dsb\n isb");
    for (uint32_t *src = &_sidata, *dst = &_sdata; dst < &_edata;) *dst++ = *src++;
    for (uint32_t* dst = &_sbss; dst < &_ebss;) *dst++ = 0;
    __libc_init_array();
    (void)main();
    for (;;) {}
}

void Default_Handler(void) {
    for (;;) {}
}

/* __libc_init_array calls _init (crti.o, not linked with -nostartfiles): an empty one. */
void _init(void) {}

__attribute__((section(".isr_vector"), used)) static void (*const vectors[16])(void) = {
    (void (*)(void))(uintptr_t)(&_estack), Reset_Handler, Default_Handler, Default_Handler, Default_Handler,
    Default_Handler, Default_Handler, 0, 0, 0, 0, Default_Handler, Default_Handler, 0, Default_Handler,
    Default_Handler,
};
