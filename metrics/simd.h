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

namespace cbr::metrics {

// A row's sum in four partial sums, (s0 + s1) + (s2 + s3): they break the add latency chain,
// and per-row sums keep the rounding near numpy's pairwise mean.
template <typename T>
[[gnu::always_inline]] inline double rowSum(const T* v, int n) {
    double s0 = 0, s1 = 0, s2 = 0, s3 = 0;
    int x = 0;
    for (; x + 4 <= n; x += 4) {
        s0 += v[x];
        s1 += v[x + 1];
        s2 += v[x + 2];
        s3 += v[x + 3];
    }
    for (; x < n; ++x) s0 += v[x];
    return (s0 + s1) + (s2 + s3);
}

}  // namespace cbr::metrics
