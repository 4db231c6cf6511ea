// Whether the tests run under a sanitizer (ASan / TSan): their shadow memory and quarantine inflate memory, and their
// checks time, so memory and time bounds hold only in an uninstrumented build.
#pragma once

#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define SWARD_TEST_SANITIZED 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define SWARD_TEST_SANITIZED 1
#endif

namespace sward::test {
#ifdef SWARD_TEST_SANITIZED
inline constexpr bool kSanitizedBuild = true;
#else
inline constexpr bool kSanitizedBuild = false;
#endif
} // namespace sward::test
