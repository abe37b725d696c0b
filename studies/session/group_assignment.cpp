#include "studies/session/group_assignment.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>

#include "core/util/csv.h"
#include "core/util/portable_random.h"

namespace handlab::studies {
namespace {

// The combination of the enrolment-assigned factors' levels for this enrolment, as one index
// (the first such factor varying slowest).
int balanced_combination(const Protocol& protocol, int combinations, int enrolment) {
  const int run = enrolment / combinations;
  std::vector<int> order(static_cast<std::size_t>(combinations));
  std::iota(order.begin(), order.end(), 0);
  util::PortableRandom random(protocol.seed ^ util::fnv1a64("groups:" + std::to_string(run)));
  random.shuffle(order);
  return order[std::size_t(enrolment % combinations)];
}

}  // namespace

const std::string& level_from_field(const BetweenFactor& f, const store::Participant& p) {
  if (numeric_participant_field(f.field)) {
    const bool age = f.field == "age";
    const double x = age ? double(p.age) : p.hand_length;
    if (const BetweenLevel* level = level_holding(f, x)) return level->name;
    // As the form takes it: years, or centimetres.
    throw std::invalid_argument(
        (age ? "The age " + util::format_number(x) + " years"
             : "The hand length " + util::format_number(100.0 * x) + " cm") +
        " is in no level of the between factor " + f.name + " (the protocol's ranges).");
  }
  const std::string& answer = f.field == "sex"          ? p.sex
                              : f.field == "handedness" ? p.handedness
                                                        : p.vr_experience;
  if (const BetweenLevel* level = level_holding(f, answer)) return level->name;
  std::string known;
  for (const BetweenLevel& level : f.levels)
    for (const std::string& v : level.values) known += (known.empty() ? "" : ", ") + v;
  throw std::invalid_argument("The " + f.field + " \"" + answer +
                              "\" is in no level of the between factor " + f.name + " (" + known +
                              ").");
}

std::vector<std::pair<std::string, std::string>> assign_groups(const Protocol& protocol,
                                                               const store::Participant& p,
                                                               int enrolment) {
  int combinations = 1;
  for (const BetweenFactor& f : protocol.between)
    if (f.assignment == GroupAssignment::kEnrolment) combinations *= int(f.levels.size());
  int combination = balanced_combination(protocol, combinations, enrolment);
  std::vector<int> by_enrolment;  // each enrolment-assigned factor's level, first slowest
  for (auto f = protocol.between.rbegin(); f != protocol.between.rend(); ++f)
    if (f->assignment == GroupAssignment::kEnrolment) {
      by_enrolment.insert(by_enrolment.begin(), combination % int(f->levels.size()));
      combination /= int(f->levels.size());
    }
  std::vector<std::pair<std::string, std::string>> groups;
  std::size_t next = 0;
  for (const BetweenFactor& f : protocol.between)
    groups.emplace_back(f.name, f.assignment == GroupAssignment::kEnrolment
                                    ? f.levels[std::size_t(by_enrolment[next++])].name
                                    : level_from_field(f, p));
  return groups;
}

}  // namespace handlab::studies
