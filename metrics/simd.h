// Internal to cbr_metrics: function clones for AVX2, chosen at load time by the CPU.
#pragma once

// The metrics' filters are plain loops over doubles that the compiler vectorises; an
// x86-64-v3 (AVX2) clone doubles their width while the default clone keeps the library
// running on any x86-64. The files using it are built without FMA contraction
// (metrics/CMakeLists.txt), so both clones perform the same IEEE operations and scores
// do not depend on the machine.
#if defined(__x86_64__) && defined(__ELF__) && defined(__has_attribute)
#if __has_attribute(target_clones)
#define CBR_SIMD_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#endif
#endif
#ifndef CBR_SIMD_CLONES
#define CBR_SIMD_CLONES
#endif
