/*
 * Board support of the demo firmware: Arm MPS2 with the AN386 image
 * (Cortex-M4F, 25 MHz system clock), as emulated by qemu-system-arm.
 */
#ifndef FW_BOARD_H
#define FW_BOARD_H

#include <stdint.h>

/* Ticks of the CMSDK APB timer 0 (25 MHz), counting up, wrapping at 2^32.
 * Under QEMU with -icount shift=0 one instruction advances the virtual
 * clock by 1 ns, so one tick is 40 instructions (calibrated at start-up). */
uint32_t fw_board_ticks(void);

/* Bytes of the main stack never written since reset (painted by startup.S):
 * stack size minus the high-water mark. */
uint32_t fw_board_stack_unused(void);
/* Total bytes reserved for the main stack by the linker script. */
uint32_t fw_board_stack_size(void);

/* Executes exactly 2·iterations instructions (a SUBS/BNE loop), for the
 * calibration of the timer against the instruction count. */
void fw_board_spin(uint32_t iterations);

/* Entry point called by the reset handler; returns the exit status. */
int fw_board_main(void);

/* End the program (semihosting exit) with this status. */
void fw_exit(int status) __attribute__((noreturn));

#endif
