// Whether the tests run under AddressSanitizer and UBSan (the sanitize preset, where code runs
// 5-15 times slower). A few of the slowest tests then run the part of their cases that goes
// through every code path the rest do; the whole runs in the Release tree (docs/development.md
// lists them and why).
#pragma once

namespace handlab::test {

#ifdef HANDLAB_UNDER_SANITIZERS
inline constexpr bool kUnderSanitizers = true;
#else
inline constexpr bool kUnderSanitizers = false;
#endif

}  // namespace handlab::test
