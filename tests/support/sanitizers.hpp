// Which sanitizer a test binary was built with (GCC defines __SANITIZE_*__, clang answers
// __has_feature): FOVEAL_TEST_ASAN, FOVEAL_TEST_TSAN, and FOVEAL_TEST_SANITIZED for either.
#pragma once

#if defined(__SANITIZE_ADDRESS__)
#define FOVEAL_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define FOVEAL_TEST_ASAN 1
#endif
#endif

#if defined(__SANITIZE_THREAD__)
#define FOVEAL_TEST_TSAN 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define FOVEAL_TEST_TSAN 1
#endif
#endif

#if defined(FOVEAL_TEST_ASAN) || defined(FOVEAL_TEST_TSAN)
#define FOVEAL_TEST_SANITIZED 1
#endif
