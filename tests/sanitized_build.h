// Whether this test binary is built with AddressSanitizer. Such a build runs about ten
// times slower; a few long tests then do a shorter share of their work (the Release suite
// does all of it), because the sanitizers look for memory errors, which the shorter share
// reaches just the same.
#pragma once

namespace cyclone::test {

#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kSanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kSanitized = true;
#else
inline constexpr bool kSanitized = false;
#endif
#else
inline constexpr bool kSanitized = false;
#endif

}  // namespace cyclone::test
