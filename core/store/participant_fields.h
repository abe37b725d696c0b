// What a participant's recorded fields may hold: the rules the study database's CHECK
// constraints enforce (core/store/study_schema.cpp, which never changes once shipped), for the
// code that checks values before they reach it (the enrolment form, the protocol's
// between-participants factors).
#pragma once

#include <array>
#include <string_view>

namespace handlab::store {

inline constexpr int kMinAge = 5, kMaxAge = 120;                       // years
inline constexpr double kMinHandLength = 0.10, kMaxHandLength = 0.30;  // m
inline constexpr std::array<std::string_view, 3> kSexes = {"F", "M", "X"};
inline constexpr std::array<std::string_view, 3> kHandednesses = {"right", "left", "ambidextrous"};

}  // namespace handlab::store
