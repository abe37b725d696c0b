#include "app/cli/commands/grasp_map_file.h"

#include <fstream>
#include <sstream>

#include "app/cli/arguments.h"
#include "core/util/json_value.h"

namespace handlab::cli {
namespace {

// A closing's factors from its "values" (the command line's units), as the map ran them.
sim::MappedClosing read_closing(const util::JsonValue& c) {
  sim::MappedClosing m;
  m.point.factor = c["factor"].as_string();
  m.point.level = c["level"].as_number();
  const util::JsonValue& values = c["values"];
  for (const sim::ClosingFactor& f : sim::closing_factors())
    if (const util::JsonValue* v = values.find(f.name))
      m.point.closing.*(f.field) = v->as_number() * f.scale;
  if (const util::JsonValue* r = c.find("repeat")) m.point.repeat = int(r->as_number());
  if (const util::JsonValue* shift = c.find("cube_shift_mm")) {
    m.point.closing.cube_shift_x = shift->as_array().at(0).as_number() / 1000;
    m.point.closing.cube_shift_z = shift->as_array().at(1).as_number() / 1000;
  }
  m.held = c["held"].as_bool();
  m.released = c["released"].as_bool();
  return m;
}

}  // namespace

std::vector<MappedCube> read_grasp_map(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw UsageError("--against: cannot read " + path);
  std::ostringstream text;
  text << in.rdbuf();
  std::vector<MappedCube> cubes;
  try {
    const util::JsonValue root = util::JsonValue::parse(text.str());
    for (const util::JsonValue& cube : root["cubes"].as_array()) {
      MappedCube m;
      m.cube_size = cube["cube_size_m"].as_number();
      for (const util::JsonValue& c : cube["closings"].as_array())
        m.closings.push_back(read_closing(c));
      cubes.push_back(std::move(m));
    }
  } catch (const util::JsonError& e) {
    throw UsageError("--against: " + path + " is not a map of sim grasp --json: " + e.what());
  }
  return cubes;
}

}  // namespace handlab::cli
