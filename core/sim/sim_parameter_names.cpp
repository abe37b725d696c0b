#include "core/sim/sim_parameter_names.h"

#include <stdexcept>

namespace handlab::sim {
namespace {

struct NamedParameter {
  const char* name;
  double SimParameters::*field;
  bool positive;  // must be above zero, not only zero or more
};

// Switches, set by 1 (on) or 0 (off).
struct NamedSwitch {
  const char* name;
  bool SimParameters::*field;
};

const std::vector<NamedSwitch>& named_switches() {
  static const std::vector<NamedSwitch> table = {
      {"contact_keeps_face", &SimParameters::contact_keeps_face},
      {"contact_substeps_cube", &SimParameters::contact_substeps_cube},
      {"cube_substeps_on_floor", &SimParameters::cube_substeps_on_floor},
  };
  return table;
}

const std::vector<NamedParameter>& named_parameters() {
  static const std::vector<NamedParameter> table = {
      {"time_step", &SimParameters::time_step, true},
      {"flesh_density", &SimParameters::flesh_density, true},
      {"stiffening_strain", &SimParameters::stiffening_strain, true},
      {"stiffening_factor", &SimParameters::stiffening_factor, false},
      {"short_step_excess", &SimParameters::short_step_excess, false},
      {"bone_density", &SimParameters::bone_density, true},
      {"coupling_stiffness", &SimParameters::coupling_stiffness, true},
      {"joint_stiffness", &SimParameters::joint_stiffness, true},
      {"tracking_stiffness", &SimParameters::tracking_stiffness, true},
      {"tracking_torsion", &SimParameters::tracking_torsion, true},
      {"tracking_force_limit", &SimParameters::tracking_force_limit, false},
      {"tracking_torque_limit", &SimParameters::tracking_torque_limit, false},
      {"tracking_damping", &SimParameters::tracking_damping, false},
      {"tracking_damping_speed", &SimParameters::tracking_damping_speed, false},
      {"contact_stiffness", &SimParameters::contact_stiffness, true},
      {"contact_stiffening", &SimParameters::contact_stiffening, false},
      {"contact_damping", &SimParameters::contact_damping, false},
      {"cube_floor_stiffness", &SimParameters::cube_floor_stiffness, true},
      {"cube_floor_stiffening", &SimParameters::cube_floor_stiffening, false},
      {"friction", &SimParameters::friction, false},
      {"skin_friction", &SimParameters::skin_friction, false},
      {"cube_density", &SimParameters::cube_density, true},
      {"contact_time_step", &SimParameters::contact_time_step, false},
      {"contact_substep_window", &SimParameters::contact_substep_window, false},
  };
  return table;
}

}  // namespace

std::vector<std::string> sim_parameter_names() {
  std::vector<std::string> names;
  for (const NamedParameter& p : named_parameters()) names.push_back(p.name);
  for (const NamedSwitch& p : named_switches()) names.push_back(p.name);
  return names;
}

void set_sim_parameter(SimParameters& parameters, const std::string& name, double value) {
  for (const NamedParameter& p : named_parameters()) {
    if (name != p.name) continue;
    if (p.positive ? !(value > 0) : !(value >= 0))
      throw std::invalid_argument(name + (p.positive ? " must be above 0" : " must be 0 or more"));
    parameters.*(p.field) = value;
    return;
  }
  for (const NamedSwitch& p : named_switches()) {
    if (name != p.name) continue;
    if (value != 0 && value != 1) throw std::invalid_argument(name + " must be 0 or 1");
    parameters.*(p.field) = value == 1;
    return;
  }
  std::string names;
  for (const std::string& n : sim_parameter_names()) names += (names.empty() ? "" : ", ") + n;
  throw std::invalid_argument("no simulator parameter '" + name + "' (" + names + ")");
}

}  // namespace handlab::sim
