#include "studies/protocol/between_factor.h"

#include <algorithm>
#include <cctype>
#include <string_view>

#include "core/store/participant_fields.h"

namespace handlab::studies {
namespace {

using util::JsonValue;

constexpr const char* kTextFields[] = {"vr_experience", "sex", "handedness"};
constexpr const char* kNumericFields[] = {"age", "hand_length"};

std::string folded(std::string text) {
  const auto space = [](unsigned char c) { return std::isspace(c) != 0; };
  text.erase(text.begin(), std::find_if_not(text.begin(), text.end(), space));
  text.erase(std::find_if_not(text.rbegin(), text.rend(), space).base(), text.end());
  for (char& c : text) c = char(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

GroupAssignment read_assignment(const ProtocolReader& r, const JsonValue& f,
                                const std::string& where, std::string& field) {
  if (!f.find("assignment"))
    r.fail(where,
           "\"assignment\" is required: \"enrolment\" (balanced in order of enrolment) "
           "or the participant field that decides (vr_experience, sex, handedness, age, "
           "hand_length)");
  const std::string rule = r.text(f, "assignment", where);
  if (rule == "enrolment") return GroupAssignment::kEnrolment;
  const bool known = std::count(std::begin(kTextFields), std::end(kTextFields), rule) +
                         std::count(std::begin(kNumericFields), std::end(kNumericFields), rule) >
                     0;
  if (!known)
    r.fail(where + ".assignment", "\"" + rule +
                                      "\" is not \"enrolment\" nor a participant field "
                                      "(vr_experience, sex, handedness, age, hand_length)");
  field = rule;
  return GroupAssignment::kParticipantField;
}

// Sex and handedness take the store's few answers; the VR experience is free text.
bool answer_possible(const std::string& field, const std::string& answer) {
  auto in = [&](const auto& allowed) {
    return std::any_of(allowed.begin(), allowed.end(), [&](std::string_view a) {
      return folded(std::string(a)) == folded(answer);
    });
  };
  return field == "sex"          ? in(store::kSexes)
         : field == "handedness" ? in(store::kHandednesses)
                                 : true;
}

std::string possible_answers(const std::string& field) {
  std::string out;
  for (std::string_view a : field == "sex" ? store::kSexes : store::kHandednesses)
    out += (out.empty() ? "" : ", ") + std::string(a);
  return out;
}

BetweenLevel read_level(const ProtocolReader& r, const BetweenFactor& factor, const JsonValue& v,
                        const std::string& where) {
  BetweenLevel level;
  if (factor.assignment == GroupAssignment::kEnrolment) {
    r.check_keys(v, where, {"name"});
  } else if (numeric_participant_field(factor.field)) {
    r.check_keys(v, where, {"name", "from", "below"});
    level.from = r.number(v, "from", where, 0.0, 1000.0, level.from);
    level.below = r.number(v, "below", where, 0.0, 1000.0, level.below);
    if (!v.find("from") && !v.find("below"))
      r.fail(where, "give \"from\", \"below\" or both: the range of " + factor.field +
                        " that places a participant in this level");
    if (!(level.from < level.below)) r.fail(where, "\"from\" must be below \"below\"");
    // A level no enrolled participant can be in would stay empty.
    const bool age = factor.field == "age";
    const double lo = age ? store::kMinAge : store::kMinHandLength;
    const double hi = age ? store::kMaxAge : store::kMaxHandLength;
    if (level.from > hi || level.below <= lo)
      r.fail(where, "no participant's " + factor.field + " is in its range (the form takes " +
                        (age ? "5-120 years" : "0.10-0.30 m") + ")");
  } else {
    r.check_keys(v, where, {"name", "values"});
    const JsonValue* values = v.find("values");
    if (!values || !values->is_array() || values->size() == 0)
      r.fail(where, "\"values\" must list the " + factor.field +
                        " answers that place a participant in this level");
    for (const JsonValue& x : values->as_array()) {
      if (!x.is_string() || folded(x.as_string()).empty())
        r.fail(where + ".values", "values are non-empty strings");
      level.values.push_back(x.as_string());
      if (!answer_possible(factor.field, x.as_string()))
        r.fail(where + ".values", "\"" + x.as_string() + "\" is not a " + factor.field +
                                      " the form takes (" + possible_answers(factor.field) + ")");
    }
  }
  level.name = r.text(v, "name", where);
  return level;
}

// Text values in one level only (compared as the form's answers are: case and spaces aside);
// numeric ranges that do not overlap.
void check_levels_disjoint(const ProtocolReader& r, const BetweenFactor& factor,
                           const std::string& where) {
  if (factor.assignment == GroupAssignment::kEnrolment) return;
  for (std::size_t a = 0; a < factor.levels.size(); ++a)
    for (std::size_t b = a + 1; b < factor.levels.size(); ++b) {
      const BetweenLevel &x = factor.levels[a], &y = factor.levels[b];
      for (const std::string& v : x.values)
        for (const std::string& w : y.values)
          if (folded(v) == folded(w))
            r.fail(where + ".levels[" + std::to_string(b) + "].values",
                   "\"" + w + "\" is a value of level \"" + x.name + "\" too");
      if (numeric_participant_field(factor.field) && x.from < y.below && y.from < x.below)
        r.fail(where + ".levels[" + std::to_string(b) + "]",
               "its range overlaps level \"" + x.name + "\"'s");
    }
}

}  // namespace

std::string assignment_rule(const BetweenFactor& factor, const std::string& field_name) {
  return factor.assignment == GroupAssignment::kEnrolment ? "balanced in order of enrolment"
                                                          : "by " + field_name;
}

bool numeric_participant_field(const std::string& field) {
  return std::count(std::begin(kNumericFields), std::end(kNumericFields), field) > 0;
}

const BetweenLevel* level_holding(const BetweenFactor& factor, const std::string& answer) {
  for (const BetweenLevel& level : factor.levels)
    for (const std::string& v : level.values)
      if (folded(v) == folded(answer)) return &level;
  return nullptr;
}

const BetweenLevel* level_holding(const BetweenFactor& factor, double number) {
  for (const BetweenLevel& level : factor.levels)
    if (number >= level.from && number < level.below) return &level;
  return nullptr;
}

std::vector<BetweenFactor> read_between_factors(const ProtocolReader& r, const JsonValue& between,
                                                const std::set<std::string>& taken) {
  if (!between.is_array()) r.fail("between", "must be an array of factors");
  std::vector<BetweenFactor> out;
  std::set<std::string> names = taken;
  for (std::size_t i = 0; i < between.size(); ++i) {
    const std::string where = "between[" + std::to_string(i) + "]";
    const JsonValue& f = between[i];
    r.check_keys(f, where, {"name", "assignment", "levels"});
    BetweenFactor factor;
    factor.name = r.column_name(f, "name", where);
    if (!names.insert(factor.name).second)
      r.fail(where + ".name", "\"" + factor.name +
                                  "\" is taken (by a factor or a column of the exports); name "
                                  "the between factor otherwise");
    factor.assignment = read_assignment(r, f, where, factor.field);
    factor.levels = r.levels(f, where, factor.name, [&](const JsonValue& v, const std::string& at) {
      return read_level(r, factor, v, at);
    });
    check_levels_disjoint(r, factor, where);
    out.push_back(std::move(factor));
  }
  return out;
}

}  // namespace handlab::studies
