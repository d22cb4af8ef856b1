#pragma once
// Whether this test program (and the dabench it runs) is built with AddressSanitizer or
// ThreadSanitizer (scripts/test_sanitizers.sh), which slow the code under test 5–20 times. A
// system-level test that needs a long run only so that it has something to interrupt sizes the
// run by it: the same code paths, in a run that lasts about as long as in the release build. So
// does a test that asserts the same thing of each of several instances: every option and branch
// it covers, on fewer instances.
namespace dabench::test {

#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define DABENCH_TEST_SANITIZED 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define DABENCH_TEST_SANITIZED 1
#endif

#ifdef DABENCH_TEST_SANITIZED
inline constexpr bool kSanitized = true;
#else
inline constexpr bool kSanitized = false;
#endif

// `release` in the release build, `release / slowdown` (at least 1) under a sanitizer.
inline constexpr int sanitized_size(int release, int slowdown) {
  return kSanitized ? (release / slowdown > 0 ? release / slowdown : 1) : release;
}

}  // namespace dabench::test
