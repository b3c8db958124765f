// CBR_SANITIZED: this translation unit is built with AddressSanitizer or ThreadSanitizer.
// GCC says so with __SANITIZE_ADDRESS__ / __SANITIZE_THREAD__; clang 14 (Debian 12) only
// through __has_feature.
#pragma once

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define CBR_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define CBR_SANITIZED 1
#endif
#endif
