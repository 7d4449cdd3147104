/* WP_COMPUTED_HERE(v): the float4 v is computed by this point of the
 * program, not later.
 *
 * The compiler moves a pure computation down to the block that first uses
 * it (LLVM's instruction and machine-code sinking), which is right for work
 * that a branch may skip, but undoes a computation placed early on purpose:
 * a long chain of latency (the Sobol numbers, rng.h) that the processor can
 * overlap with independent work only if it comes first in program order. An
 * empty assembly statement that reads v pins it: v must be in a register
 * there, and the statement (volatile) stays where it is. It emits no
 * instruction. Only where the kernel is compiled for an x86-64 CPU ("x": an
 * SSE register); elsewhere nothing, as with the prefetch hints
 * (prefetch.h). */
#ifndef WP_COMPUTED_HERE_H
#define WP_COMPUTED_HERE_H

#if defined(__clang__) && defined(__x86_64__)
#define WP_COMPUTED_HERE(v) __asm__ volatile("" : : "x"(v))
#else
#define WP_COMPUTED_HERE(v) ((void)(v))
#endif

#endif /* WP_COMPUTED_HERE_H */
