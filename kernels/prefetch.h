/* Prefetch hints: the 64-byte line at `address` is wanted soon, to be read
 * (WP_PREFETCH_LINE) or written (WP_PREFETCH_LINE_FOR_WRITE).
 *
 * OpenCL's own prefetch() compiles to nothing on PoCL 3.1 (no prefetch
 * instruction in the kernel's code), Clang's builtin to the CPU's prefetch
 * instruction. Only where the kernel is compiled for a CPU: for other targets
 * the builtin becomes an llvm.prefetch call that some cannot run (Oclgrind,
 * which compiles for SPIR, stops on it as an undefined function); there
 * nothing. Used by the any-hit walk (bvh_any_hit.h) and shade's look-ahead
 * (shade.cl). */
#ifndef WP_PREFETCH_H
#define WP_PREFETCH_H

#if defined(__clang__) && (defined(__x86_64__) || defined(__aarch64__))
#define WP_PREFETCH_LINE(address) __builtin_prefetch((__global const char*)(address))
#define WP_PREFETCH_LINE_FOR_WRITE(address) __builtin_prefetch((__global const char*)(address), 1)
#else
#define WP_PREFETCH_LINE(address) ((void)(address))
#define WP_PREFETCH_LINE_FOR_WRITE(address) ((void)(address))
#endif

#endif /* WP_PREFETCH_H */
