/* MPS2-AN386 board support: timer, stack watermark, faults, exit. */
#include "board.h"

#include "semihost.h"

/* CMSDK APB timer 0 (AN386: 0x40000000), registers as 32-bit words. */
#define TIMER0 ((volatile uint32_t *)0x40000000u)
enum { TIMER_CTRL = 0, TIMER_VALUE = 1, TIMER_RELOAD = 2 };

/* Symbols of the linker script. */
extern uint32_t __stack_limit[], __stack_top[];

#define STACK_PAINT 0x5AC55AC5u

static int timer_started;

static void timer_start(void)
{
    TIMER0[TIMER_CTRL] = 0;
    TIMER0[TIMER_RELOAD] = 0xFFFFFFFFu;
    TIMER0[TIMER_VALUE] = 0xFFFFFFFFu;
    TIMER0[TIMER_CTRL] = 1; /* enable, no interrupt, internal clock */
    timer_started = 1;
}

uint32_t fw_board_ticks(void)
{
    if (!timer_started) timer_start();
    /* The timer counts down from 2^32 - 1. */
    return 0xFFFFFFFFu - TIMER0[TIMER_VALUE];
}

uint32_t fw_board_stack_size(void)
{
    return (uint32_t)((uintptr_t)__stack_top - (uintptr_t)__stack_limit);
}

uint32_t fw_board_stack_unused(void)
{
    const volatile uint32_t *p = __stack_limit;
    while (p < __stack_top && *p == STACK_PAINT) p++;
    return (uint32_t)((uintptr_t)p - (uintptr_t)__stack_limit);
}

void fw_board_spin(uint32_t iterations)
{
    if (iterations == 0) return;
    __asm__ volatile("1: subs %0, %0, #1\n\tbne 1b" : "+r"(iterations) : : "cc");
}

void fw_exit(int status) { fw_semihost_exit(status); }

/* Every fault and unexpected exception: say so and stop with status 3. */
void fw_fault_handler(void);
void fw_fault_handler(void)
{
    fw_semihost_write0("\nfault: unexpected exception, stopping\n");
    fw_semihost_exit(3);
}
