#include "studies/participant/participant_memory.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/util/json_value.h"
#include "core/util/json_writer.h"

namespace handlab::studies {
namespace {

bool same_size(double a, double b) {
  return std::abs(a - b) < 0.0005;
}

}  // namespace

const CubeMemory* ParticipantMemory::cube(double size) const {
  for (const CubeMemory& c : cubes)
    if (same_size(c.cube_size, size)) return &c;
  return nullptr;
}

TwoRateState after_closing(const TwoRateState& contact, const std::optional<double>& error,
                           const TwoRateRates& rates) {
  return error ? adapt(contact, rates, *error) : forget(contact, rates);
}

ParticipantMemory remember(const ParticipantMemory& memory, const TrialExperience& trial,
                           const TwoRateRates& rates, double grip_retention) {
  ParticipantMemory next = memory;
  ++next.trials;
  CubeMemory* cube = nullptr;
  for (CubeMemory& c : next.cubes)
    if (same_size(c.cube_size, trial.cube_size)) cube = &c;
  if (!cube) {
    next.cubes.emplace_back();
    next.cubes.back().cube_size = trial.cube_size;
    cube = &next.cubes.back();
  }
  ++cube->trials;
  for (const std::optional<double>& error : trial.contact_errors)
    cube->contact = after_closing(cube->contact, error, rates);
  // The visuomotor map of grasping adapts by offsets (Safstrom & Edin 2005, shown for the grip
  // aperture; for the aim, an assumption): each closing whose pad touched the cube is a
  // movement of the two-state model along each axis.
  for (const std::array<double, 2>& error : trial.aim_errors) {
    cube->aim_x = adapt(cube->aim_x, rates, error[0]);
    cube->aim_z = adapt(cube->aim_z, rates, error[1]);
  }
  // A lift's grip and digit placement are programmed from the lifts before (Johansson &
  // Westling 1988; Lukos, Ansuini & Santello 2007): what a slip taught is kept, and decays
  // slowly over the trials without one, by their count (Witney, Goodbody & Wolpert 2000).
  if (trial.slips > 0) {
    cube->grip_margin += trial.squeeze_added;
    cube->grasp_lower += trial.lowered;
  } else {
    cube->grip_margin *= grip_retention;
    cube->grasp_lower *= grip_retention;
  }
  // People slow down after an error (Rabbitt 1966), and set their speed by what their own
  // speed-accuracy trade-off costs them (Dean, Wu & Maloney 2007): the caution a failed grasp
  // raised is carried, and relaxes as grasps hold.
  cube->caution = adapt(cube->caution, rates, trial.caution_added);
  return next;
}

std::string memory_to_json(const ParticipantMemory& m) {
  std::ostringstream out;
  util::JsonWriter w(out, 0);
  w.begin_object().field("trials", m.trials).key("cubes").begin_array();
  for (const CubeMemory& c : m.cubes)
    w.begin_object()
        .field("cube_size", c.cube_size)
        .field("trials", c.trials)
        .field("contact_fast", c.contact.fast)
        .field("contact_slow", c.contact.slow)
        .field("grip_margin", c.grip_margin)
        .field("grasp_lower", c.grasp_lower)
        .field("caution_fast", c.caution.fast)
        .field("caution_slow", c.caution.slow)
        .field("aim_x_fast", c.aim_x.fast)
        .field("aim_x_slow", c.aim_x.slow)
        .field("aim_z_fast", c.aim_z.fast)
        .field("aim_z_slow", c.aim_z.slow)
        .end_object();
  w.end_array().end_object();
  return out.str();
}

ParticipantMemory memory_from_json(const std::string& text) {
  try {
    const util::JsonValue v = util::JsonValue::parse(text);
    ParticipantMemory m;
    m.trials = int(v["trials"].as_number());
    // Models before 2.3 kept no caution, before 2.6 no aim: a record of theirs reads with none.
    auto optional = [](const util::JsonValue& c, const char* key) {
      const util::JsonValue* found = c.find(key);
      return found ? found->as_number() : 0.0;
    };
    // Models before 2.7 kept the grip margin as two states (their sum was the margin), and
    // grasped where they first chose.
    auto grip_margin = [&](const util::JsonValue& c) {
      return c.find("grip_margin") ? c["grip_margin"].as_number()
                                   : c["grip_fast"].as_number() + c["grip_slow"].as_number();
    };
    for (const util::JsonValue& c : v["cubes"].as_array())
      m.cubes.push_back({c["cube_size"].as_number(),
                         int(c["trials"].as_number()),
                         {c["contact_fast"].as_number(), c["contact_slow"].as_number()},
                         grip_margin(c),
                         optional(c, "grasp_lower"),
                         {optional(c, "caution_fast"), optional(c, "caution_slow")},
                         {optional(c, "aim_x_fast"), optional(c, "aim_x_slow")},
                         {optional(c, "aim_z_fast"), optional(c, "aim_z_slow")}});
    return m;
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("not a simulated participant's memory: ") + e.what());
  }
}

}  // namespace handlab::studies
