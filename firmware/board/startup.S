/*
 * Reset handler and vector table of the demo firmware (Cortex-M4F).
 * Written in assembly because the FPU must be enabled (CPACR) before the
 * first floating-point instruction, which C code may emit anywhere.
 */
    .syntax unified
    .cpu cortex-m4
    .fpu fpv4-sp-d16
    .thumb

    .section .isr_vector, "a", %progbits
    .align 2
    .global fw_vectors
fw_vectors:
    .word __stack_top           /* initial MSP */
    .word fw_reset_handler      /* reset */
    .word fw_fault_handler      /* NMI */
    .word fw_fault_handler      /* HardFault */
    .word fw_fault_handler      /* MemManage */
    .word fw_fault_handler      /* BusFault */
    .word fw_fault_handler      /* UsageFault */
    .word 0, 0, 0, 0            /* reserved */
    .word fw_fault_handler      /* SVCall */
    .word fw_fault_handler      /* DebugMonitor */
    .word 0                     /* reserved */
    .word fw_fault_handler      /* PendSV */
    .word fw_fault_handler      /* SysTick (not enabled) */

    .text
    .thumb_func
    .global fw_reset_handler
    .type fw_reset_handler, %function
fw_reset_handler:
    /* CPACR: full access to coprocessors 10 and 11 (the FPU). */
    ldr r0, =0xE000ED88
    ldr r1, [r0]
    orr r1, r1, #(0xF << 20)
    str r1, [r0]
    dsb
    isb
    /* Copy .data from its load address. */
    ldr r0, =__data_start
    ldr r1, =__data_end
    ldr r2, =__data_load
1:  cmp r0, r1
    bhs 2f
    ldr r3, [r2], #4
    str r3, [r0], #4
    b 1b
2:  /* Zero .bss. */
    ldr r0, =__bss_start
    ldr r1, =__bss_end
    movs r3, #0
3:  cmp r0, r1
    bhs 4f
    str r3, [r0], #4
    b 3b
4:  /* Paint the stack below the current frame for the high-water mark. */
    ldr r0, =__stack_limit
    mov r1, sp
    subs r1, r1, #64
    ldr r3, =0x5AC55AC5
5:  cmp r0, r1
    bhs 6f
    str r3, [r0], #4
    b 5b
6:  bl fw_board_main
    /* fw_board_main returns the exit status in r0. */
    bl fw_exit
7:  b 7b
    .size fw_reset_handler, . - fw_reset_handler
    .pool
