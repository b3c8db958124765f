// Internal to cbr_metrics: the per-frame maps' storage, allocated so that it faults in cheaply.
#pragma once

#include <sys/mman.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace cbr::metrics::detail {

// Asks for transparent huge pages over [data, data + bytes) before it is first touched. A
// 1080p map of doubles (16 MB) then takes about 8 page faults instead of 4000, which cost a
// few milliseconds per map on the calling thread where the kernel lends huge pages on
// request only (THP "madvise" mode, Debian's default). Where the advice is refused or
// unknown, the pages are plain ones, as before.
inline void adviseHugePages(const void* data, size_t bytes) {
#ifdef MADV_HUGEPAGE
    constexpr uintptr_t kHuge = uintptr_t(2) << 20;
    const uintptr_t begin = (reinterpret_cast<uintptr_t>(data) + kHuge - 1) & ~(kHuge - 1);
    const uintptr_t end = (reinterpret_cast<uintptr_t>(data) + bytes) & ~(kHuge - 1);
    if (end > begin) (void)madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#else
    (void)data;
    (void)bytes;
#endif
}

// n copies of value (a map) in advised pages.
template <typename T>
std::vector<T> filledBuffer(size_t n, T value) {
    std::vector<T> v;
    v.reserve(n);
    adviseHugePages(v.data(), n * sizeof(T));
    v.assign(n, value);
    return v;
}

// n values left uninitialised, for scratch that is written before it is read: the worker
// threads that write it then take its page faults, in parallel, instead of the caller.
template <typename T>
std::unique_ptr<T[]> scratchBuffer(size_t n) {
    std::unique_ptr<T[]> p(new T[n]);
    adviseHugePages(p.get(), n * sizeof(T));
    return p;
}

}  // namespace cbr::metrics::detail
