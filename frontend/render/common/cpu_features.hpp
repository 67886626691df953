// What the CPU this process runs on can execute: the host renderers choose
// their SIMD paths by it (AVX for the double lanes of the sample chain and
// covers4, AVX2 and FMA for the fast coverage test and the sample pattern),
// each with a scalar path that gives the same results elsewhere. False off x86.
#pragma once

namespace blurcull::frontend {

#if defined(__x86_64__) || defined(__i386__)
inline bool cpu_has_avx() {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx");
}
inline bool cpu_has_avx2() {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2");
}
inline bool cpu_has_fma() {
    __builtin_cpu_init();
    return __builtin_cpu_supports("fma");
}
#else
inline bool cpu_has_avx() { return false; }
inline bool cpu_has_avx2() { return false; }
inline bool cpu_has_fma() { return false; }
#endif

}  // namespace blurcull::frontend
