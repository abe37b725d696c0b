#include "studies/protocol/protocol.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <numeric>
#include <set>
#include <sstream>

#include "core/util/data_files.h"
#include "core/util/json_value.h"
#include "core/util/portable_random.h"
#include "studies/protocol/block_schedule.h"
#include "studies/protocol/export_columns.h"

namespace handlab::studies {
namespace {

using util::JsonValue;

// A cube's side: 5-150 mm, from a fingertip pinch to a whole-hand grasp (2-200 mm in the
// protocol of a study made before that rule).
double cube_size(const ProtocolReader& r, const JsonValue& object, const std::string& where,
                 std::optional<double> fallback) {
  if (r.stored()) return r.length(object, "cube_size", where, 0.002, 0.2, fallback);
  return r.length(object, "cube_size", where, 0.005, 0.15, fallback);
}

// "blocks": the blocks whose trials ask the questionnaire, with "when": "blocks" only.
std::vector<int> questionnaire_blocks(const ProtocolReader& r, const JsonValue& questionnaire,
                                      const Protocol& p) {
  const JsonValue* listed = questionnaire.find("blocks");
  const bool given = p.questionnaire_timing == QuestionnaireTiming::kGivenBlocks;
  if (!given) {
    if (listed) r.fail("questionnaire.blocks", "needs \"when\": \"blocks\"");
    return {};
  }
  if (!listed || !listed->is_array() || listed->size() == 0)
    r.fail("questionnaire.blocks", "must list the blocks (1 to " + std::to_string(p.blocks) +
                                       ") after whose trials the questionnaire is asked");
  std::set<int> blocks;
  for (const JsonValue& b : listed->as_array()) {
    const double x = b.is_number() ? b.as_number() : 0.0;
    if (x != std::floor(x) || x < 1 || x > p.blocks)
      r.fail("questionnaire.blocks", "a block is a number from 1 to " + std::to_string(p.blocks));
    if (!blocks.insert(int(x)).second)
      r.fail("questionnaire.blocks", "block " + std::to_string(int(x)) + " appears twice");
  }
  return {blocks.begin(), blocks.end()};
}

Level parse_level(const ProtocolReader& r, const std::string& factor, const JsonValue& v,
                  const std::string& where) {
  Level level;
  if (factor == "strategy") {
    r.check_keys(v, where, {"name", "method", "parameters"});
    level.name = r.text(v, "name", where);
    level.method = read_strategy_method(r, v, where);
  } else if (factor == "manipulation") {
    r.check_keys(v, where, {"name", "cube_size"});
    level.name = r.text(v, "name", where);
    level.cube_size = cube_size(r, v, where, std::nullopt);
  } else if (factor == "hand_length") {
    r.check_keys(v, where, {"name", "length"});
    level.name = r.text(v, "name", where);
    level.hand_length = r.length(v, "length", where, 0.10, 0.30);
  }
  return level;
}

}  // namespace

std::vector<Condition> Protocol::conditions() const {
  std::vector<Condition> out;
  std::vector<int> index(factors.size(), 0);
  while (true) {
    Condition c;
    c.levels = index;
    c.strategy = strategy;
    c.cube_size = scene.cube_size;
    c.simulated_hand_length = simulated_hand_length;
    for (std::size_t f = 0; f < factors.size(); ++f) {
      const Level& level = factors[f].levels[std::size_t(index[f])];
      c.label += (f ? "-" : "") + level.name;
      if (level.method) c.strategy = *level.method;
      if (level.cube_size) c.cube_size = *level.cube_size;
      if (level.hand_length) c.simulated_hand_length = *level.hand_length;
    }
    c.simulated_hand = hand::HandShape::with_length(c.simulated_hand_length);
    c.simulated_hand.tissue = simulated_hand_tissue;
    // A breadth given for the protocol's hand scales with the condition's length.
    if (simulated_hand_breadth > 0)
      c.simulated_hand.breadth =
          simulated_hand_breadth * c.simulated_hand_length / simulated_hand_length;
    if (factors.empty()) c.label = "task";
    out.push_back(std::move(c));
    // Odometer: the last factor varies fastest.
    int f = int(factors.size()) - 1;
    for (; f >= 0; --f) {
      if (++index[std::size_t(f)] < int(factors[std::size_t(f)].levels.size())) break;
      index[std::size_t(f)] = 0;
    }
    if (f < 0) break;
  }
  return out;
}

bool Protocol::asks_questionnaire(int block) const {
  switch (questionnaire_timing) {
    case QuestionnaireTiming::kNever:
      return false;
    case QuestionnaireTiming::kLastBlock:
      return block == blocks;
    case QuestionnaireTiming::kEveryTrial:
      return block >= 1;
    case QuestionnaireTiming::kGivenBlocks:
      return std::find(questionnaire_blocks.begin(), questionnaire_blocks.end(), block) !=
             questionnaire_blocks.end();
  }
  return false;
}

std::string Protocol::questionnaire_schedule() const {
  switch (questionnaire_timing) {
    case QuestionnaireTiming::kNever:
      return "never";
    case QuestionnaireTiming::kLastBlock:
      return "after each trial of the last block";
    case QuestionnaireTiming::kEveryTrial:
      return "after every trial";
    case QuestionnaireTiming::kGivenBlocks:
      break;
  }
  std::string list;
  for (std::size_t k = 0; k < questionnaire_blocks.size(); ++k)
    list += (k == 0                                 ? ""
             : k + 1 == questionnaire_blocks.size() ? " and "
                                                    : ", ") +
            std::to_string(questionnaire_blocks[k]);
  return "after each trial of block" + std::string(questionnaire_blocks.size() > 1 ? "s " : " ") +
         list;
}

int Protocol::factor_index(const std::string& name) const {
  for (std::size_t f = 0; f < factors.size(); ++f)
    if (factors[f].name == name) return int(f);
  return -1;
}

Protocol parse_protocol(const std::string& text, const std::string& source_name,
                        ProtocolSource source) {
  const ProtocolReader r(source_name, source == ProtocolSource::kStoredStudy);
  JsonValue root;
  try {
    root = JsonValue::parse(text);
  } catch (const util::JsonError& e) {
    throw ProtocolError(source_name + ": " + e.what());
  }
  r.check_keys(root, "protocol",
               {"format", "version", "name", "title", "seed", "factors", "blocks",
                "counterbalancing", "practice", "questionnaire", "scene", "simulated_hand",
                "strategy", "trial", "between", "session"});
  if (r.text(root, "format", "protocol") != "handlab-protocol")
    r.fail("protocol.format", "must be \"handlab-protocol\"");
  const int version = r.integer(root, "version", "protocol", 1, 1000);
  if (version != 1)
    r.fail("protocol.version",
           "this handlab reads version 1, the file is version " + std::to_string(version));

  Protocol p;
  p.text = text;
  p.name = r.text(root, "name", "protocol");
  p.title = r.text(root, "title", "protocol", p.name);
  p.seed = std::uint64_t(r.number(root, "seed", "protocol", 0, 9007199254740991.0));
  p.blocks = r.integer(root, "blocks", "protocol", 1, 100);

  const std::string order = r.text(root, "counterbalancing", "protocol", "randomized-per-block");
  if (order == "randomized-per-block")
    p.counterbalancing = Counterbalancing::kRandomizedPerBlock;
  else if (order == "latin-square")
    p.counterbalancing = Counterbalancing::kLatinSquare;
  else if (order == "fixed")
    p.counterbalancing = Counterbalancing::kFixed;
  else
    r.fail("protocol.counterbalancing",
           "\"" + order + "\" is not one of randomized-per-block, latin-square, fixed");

  const JsonValue* factors = root.find("factors");
  if (!factors || !factors->is_array()) r.fail("protocol", "\"factors\" must be an array");
  std::set<std::string> factor_names;
  for (std::size_t i = 0; i < factors->size(); ++i) {
    const std::string where = "factors[" + std::to_string(i) + "]";
    const JsonValue& f = (*factors)[i];
    r.check_keys(f, where, {"name", "levels"});
    Factor factor;
    factor.name = r.text(f, "name", where);
    if (factor.name != "strategy" && factor.name != "manipulation" && factor.name != "hand_length")
      r.fail(where + ".name",
             "unknown factor \"" + factor.name + "\" (known: strategy, manipulation, hand_length)");
    if (!factor_names.insert(factor.name).second)
      r.fail(where + ".name", "factor \"" + factor.name + "\" appears twice");
    factor.levels = r.levels(f, where, factor.name, [&](const JsonValue& v, const std::string& at) {
      return parse_level(r, factor.name, v, at);
    });
    p.factors.push_back(std::move(factor));
  }

  // A condition's label joins its levels' with '-': free labels may meet ("a-b" and "c",
  // "a" and "b-c"), and results are kept by condition label.
  std::set<std::string> condition_labels;
  for (const Condition& c : p.conditions())
    if (!condition_labels.insert(c.label).second)
      r.fail("factors", "two conditions would both be labelled \"" + c.label +
                            "\": a level's label with '-' meets another's");

  const std::vector<std::string> columns = fixed_export_columns();
  const std::set<std::string> fixed_columns(columns.begin(), columns.end());

  if (const JsonValue* practice = root.find("practice")) {
    r.check_keys(*practice, "practice", {"trials_per_condition"});
    p.practice_per_condition = r.integer(*practice, "trials_per_condition", "practice", 0, 10);
  }

  if (const JsonValue* q = root.find("questionnaire")) {
    r.check_keys(*q, "questionnaire", {"when", "blocks", "scale_points", "items"});
    const std::string when = r.text(*q, "when", "questionnaire");
    if (when == "never")
      p.questionnaire_timing = QuestionnaireTiming::kNever;
    else if (when == "last-block")
      p.questionnaire_timing = QuestionnaireTiming::kLastBlock;
    else if (when == "every-trial")
      p.questionnaire_timing = QuestionnaireTiming::kEveryTrial;
    else if (when == "blocks")
      p.questionnaire_timing = QuestionnaireTiming::kGivenBlocks;
    else
      r.fail("questionnaire.when",
             "\"" + when + "\" is not one of never, last-block, every-trial, blocks");
    p.questionnaire_blocks = questionnaire_blocks(r, *q, p);
    p.scale_points = r.integer(*q, "scale_points", "questionnaire", 2, 11);
    const JsonValue* items = q->find("items");
    if (!items || !items->is_array() || items->size() == 0)
      r.fail("questionnaire", "\"items\" must list at least one item");
    std::set<std::string> ids;
    for (std::size_t i = 0; i < items->size(); ++i) {
      const std::string where = "questionnaire.items[" + std::to_string(i) + "]";
      const JsonValue& it = (*items)[i];
      r.check_keys(it, where, {"id", "text", "anchors"});
      QuestionnaireItem item;
      item.id = r.column_name(it, "id", where);
      if (!ids.insert(item.id).second) r.fail(where + ".id", "\"" + item.id + "\" appears twice");
      // (A study's stored protocol keeps the items it was made with.)
      if (!r.stored() && (fixed_columns.count(item.id) || factor_names.count(item.id)))
        r.fail(where + ".id", "\"" + item.id +
                                  "\" is taken (by a factor or a column of the exports); name "
                                  "the item otherwise");
      item.text = r.text(it, "text", where);
      const JsonValue* anchors = it.find("anchors");
      if (!anchors || !anchors->is_array() || int(anchors->size()) != p.scale_points)
        r.fail(where + ".anchors",
               "must give one label per scale point (" + std::to_string(p.scale_points) + ")");
      for (const JsonValue& a : anchors->as_array()) {
        if (!a.is_string()) r.fail(where + ".anchors", "labels must be strings");
        item.anchors.push_back(a.as_string());
      }
      p.items.push_back(std::move(item));
    }
  }

  if (const JsonValue* between = root.find("between")) {
    // A between factor is a column of the exports beside the within factors, the
    // participant's fields, the design's columns and the questionnaire's items.
    std::set<std::string> taken(factor_names);
    taken.insert(fixed_columns.begin(), fixed_columns.end());
    for (const QuestionnaireItem& item : p.items) taken.insert(item.id);
    p.between = read_between_factors(r, *between, taken);
  }

  if (const JsonValue* scene = root.find("scene")) {
    r.check_keys(*scene, "scene",
                 {"zone_a", "zone_b", "zone_size", "cube_size", "cube_density", "rest_time_s"});
    p.scene.zone_a = r.point(*scene, "zone_a", "scene", p.scene.zone_a);
    p.scene.zone_b = r.point(*scene, "zone_b", "scene", p.scene.zone_b);
    p.scene.zone_size = r.length(*scene, "zone_size", "scene", 0.01, 1.0, p.scene.zone_size);
    p.scene.cube_size = cube_size(r, *scene, "scene", p.scene.cube_size);
    p.cube_density = r.number(*scene, "cube_density", "scene", 10, 20000, p.cube_density);
    p.rest_time_s = r.number(*scene, "rest_time_s", "scene", 0.0, 10.0, p.rest_time_s);
    if ((p.scene.zone_a - p.scene.zone_b).norm() < p.scene.zone_size)
      r.fail("scene", "zones A and B overlap");
  }
  if (const JsonValue* hand = root.find("simulated_hand")) {
    r.check_keys(*hand, "simulated_hand", {"length", "breadth", "tissue"});
    p.simulated_hand_length = r.length(*hand, "length", "simulated_hand", 0.10, 0.30);
    p.simulated_hand_breadth = r.length(*hand, "breadth", "simulated_hand", 0.0, 0.2, 0.0);
    p.simulated_hand_tissue = r.number(*hand, "tissue", "simulated_hand", 0.5, 2.0, 1.0);
  }
  if (root.find("strategy")) {
    const std::string s = r.text(root, "strategy", "protocol");
    if (s != "naive" && s != "ours") r.fail("protocol.strategy", "is \"naive\" or \"ours\"");
    p.strategy.method = s == "naive" ? retarget::Strategy::kNaive : retarget::Strategy::kOurs;
  }
  if (const JsonValue* session = root.find("session")) {
    r.check_keys(*session, "session", {"display", "tracker"});
    if (session->find("display")) {
      const std::string d = r.text(*session, "display", "session");
      if (d != "window" && d != "headset")
        r.fail("session.display", "is \"window\" or \"headset\"");
      p.default_display = d == "headset" ? SessionDisplay::kHeadset : SessionDisplay::kWindow;
    }
    if (session->find("tracker")) {
      p.default_tracker = r.text(*session, "tracker", "session");
      if (p.default_tracker != "leap" && p.default_tracker != "openxr" &&
          p.default_tracker != "scripted" && p.default_tracker != "simulated")
        r.fail("session.tracker", "is \"leap\", \"openxr\", \"scripted\" or \"simulated\"");
    }
  }
  if (const JsonValue* trial = root.find("trial")) {
    r.check_keys(*trial, "trial", {"timeout_s"});
    p.timeout_s = r.number(*trial, "timeout_s", "trial", 1.0, 3600.0, p.timeout_s);
  }
  return p;
}

Protocol read_protocol(const std::string& named) {
  const std::string path = util::find_data_file(named);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ProtocolError("cannot read " + path);
  std::ostringstream text;
  text << in.rdbuf();
  return parse_protocol(text.str(), path);
}

std::vector<int> balanced_latin_square_row(int n, int row) {
  // Williams: 0, 1, n-1, 2, n-2, ... shifted by the row; odd n also needs the mirrored rows.
  std::vector<int> first(static_cast<std::size_t>(n));
  for (int j = 0, lo = 1, hi = n - 1; j < n; ++j)
    first[std::size_t(j)] = j == 0 ? 0 : (j % 2 == 1 ? lo++ : hi--);
  const int rows = n % 2 == 0 ? n : 2 * n;
  row %= rows;
  std::vector<int> out(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) out[std::size_t(j)] = (first[std::size_t(j)] + row % n) % n;
  if (row >= n) std::reverse(out.begin(), out.end());
  return out;
}

std::vector<PlannedTrial> plan_schedule(const Protocol& protocol, const std::string& participant,
                                        int enrolment) {
  const int n = int(protocol.conditions().size());
  std::vector<std::vector<int>> orders;
  switch (protocol.counterbalancing) {
    case Counterbalancing::kRandomizedPerBlock:
      orders = randomized_block_schedule(protocol.seed, participant, n, protocol.blocks);
      break;
    case Counterbalancing::kLatinSquare:
      orders.assign(std::size_t(protocol.blocks), balanced_latin_square_row(n, enrolment));
      break;
    case Counterbalancing::kFixed: {
      std::vector<int> fixed(static_cast<std::size_t>(n));
      std::iota(fixed.begin(), fixed.end(), 0);
      orders.assign(std::size_t(protocol.blocks), fixed);
    }
  }
  std::vector<PlannedTrial> plan;
  std::vector<int> repetitions(std::size_t(n), 0);
  if (protocol.practice_per_condition > 0) {
    // Practice: every condition, in an order of its own (a distinct stream of the seed).
    std::vector<int> practice;
    for (int k = 0; k < protocol.practice_per_condition; ++k)
      for (int c = 0; c < n; ++c) practice.push_back(c);
    util::PortableRandom random(protocol.seed ^ util::fnv1a64("practice:" + participant));
    random.shuffle(practice);
    for (std::size_t k = 0; k < practice.size(); ++k)
      plan.push_back({int(plan.size()), 0, int(k) + 1, practice[k], 0, true, false});
  }
  for (int b = 0; b < protocol.blocks; ++b) {
    const bool ask = protocol.asks_questionnaire(b + 1);
    for (int k = 0; k < n; ++k) {
      const int c = orders[std::size_t(b)][std::size_t(k)];
      plan.push_back(
          {int(plan.size()), b + 1, k + 1, c, ++repetitions[std::size_t(c)], false, ask});
    }
  }
  return plan;
}

}  // namespace handlab::studies
