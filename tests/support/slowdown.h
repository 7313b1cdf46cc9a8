// How much slower a sanitizer build checks states than a Release build: tests whose planning is
// bounded by wall time scale their limits by it (the search is the same, only slower).
#pragma once

namespace octomotion::test {

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
constexpr double kSlowdown = 5.0;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
constexpr double kSlowdown = 5.0;
#else
constexpr double kSlowdown = 1.0;
#endif
#else
constexpr double kSlowdown = 1.0;
#endif

}  // namespace octomotion::test
