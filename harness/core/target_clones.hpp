#pragma once
// DABENCH_AVX2_CLONES before a hot loop's function: GCC compiles it twice, for AVX2 and for
// baseline x86-64, and the loader picks one (target_clones, an ifunc). Empty elsewhere: off
// x86-64; under Clang, which cannot clone a function template and whose ThreadSanitizer runtime
// crashes in an instrumented ifunc resolver (it runs before the runtime starts); under GCC's
// ThreadSanitizer for the same reason. Clang builds only the sanitizer and fuzz targets.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_THREAD__)
#define DABENCH_AVX2_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define DABENCH_AVX2_CLONES
#endif
