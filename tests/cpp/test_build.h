#pragma once
// Which build this test binary is. CMake defines ADASCULPT_SANITIZED in the ASan/UBSan build (clang
// does not define gcc's __SANITIZE_ADDRESS__), where the code runs several times slower: property
// tests there run a share of their operations and quality-only tests on large meshes skip, since
// the Release ctest of the same pipeline runs them in full.
#include <algorithm>

namespace adasculpt::test {

#ifdef ADASCULPT_SANITIZED
inline constexpr bool kSanitizedBuild = true;
#else
inline constexpr bool kSanitizedBuild = false;
#endif

// n operations in Release, n / divisor (at least 1) under the sanitizers.
inline int operations_for_this_build(int n, int divisor = 4) { return kSanitizedBuild ? std::max(1, n / divisor) : n; }

}  // namespace adasculpt::test
