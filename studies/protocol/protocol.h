// A study protocol: the factors and their levels, how the conditions are ordered over the
// blocks, the questionnaire and when it is asked, the scene and the trial's limits. Read
// from a JSON file whose schema docs/study.md documents; the exact text is kept so that a
// study database can store it with its hash.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/hand/hand_shape.h"
#include "core/task/scene_layout.h"
#include "studies/protocol/between_factor.h"
#include "studies/protocol/protocol_reader.h"
#include "studies/protocol/strategy_method.h"

namespace handlab::studies {

// A level of a factor and the settings it fixes; its name is a label for people, which the
// pipeline never reads. Factors the pipeline knows:
//   strategy      levels with "method" (and "parameters")   (the retargeting)
//   manipulation  levels with "cube_size" (m)               (the cube of the task)
//   hand_length   levels with "length" (m)                  (the simulated hand's length)
struct Level {
  std::string name;
  std::optional<StrategyMethod> method;
  std::optional<double> cube_size, hand_length;
};

struct Factor {
  std::string name;
  std::vector<Level> levels;
};

// One cell of the design: a level of every factor.
struct Condition {
  std::string label;                     // levels joined by '-', e.g. "naive-gross"
  std::vector<int> levels;               // per factor
  StrategyMethod strategy;               // the strategy factor's level, or the protocol's
  double cube_size = 0.06;               // m
  double simulated_hand_length = 0.214;  // m
  hand::HandShape simulated_hand;        // the protocol's shape at that length
};

enum class Counterbalancing {
  kRandomizedPerBlock,  // each block's order drawn per participant and block (seeded)
  kLatinSquare,         // the participant's row of a balanced Latin square, every block
  kFixed,               // the conditions in protocol order
};

// After which trials the questionnaire is asked: each trial of the last block, of every
// block, or of the blocks the protocol lists (practice trials never).
enum class QuestionnaireTiming { kNever, kLastBlock, kEveryTrial, kGivenBlocks };

struct QuestionnaireItem {
  std::string id;                    // column name in exports, e.g. "precision"
  std::string text;                  // the question as shown
  std::vector<std::string> anchors;  // one label per scale point, low to high
};

// Where a session's participant looks: a window (the app's participant window, or none) or
// the OpenXR headset.
enum class SessionDisplay { kWindow, kHeadset };

struct Protocol {
  std::string name, title;
  std::uint64_t seed = 0;
  std::vector<Factor> factors;         // within participants: the conditions
  std::vector<BetweenFactor> between;  // between participants: the groups
  int blocks = 1;
  Counterbalancing counterbalancing = Counterbalancing::kRandomizedPerBlock;
  int practice_per_condition = 0;
  QuestionnaireTiming questionnaire_timing = QuestionnaireTiming::kNever;
  std::vector<int> questionnaire_blocks;  // kGivenBlocks: 1-based, ascending
  int scale_points = 5;
  std::vector<QuestionnaireItem> items;
  task::SceneLayout scene;
  double cube_density = 500.0;  // kg/m^3
  double rest_time_s = 0.5;     // the cube must rest in zone B this long
  double timeout_s = 60.0;
  StrategyMethod strategy;  // without a strategy factor ("strategy": "naive" | "ours")
  double simulated_hand_length = 0.214;
  double simulated_hand_breadth = 0.0;  // m across the MCPs; 0: 0.45 of the length
  double simulated_hand_tissue = 1.0;   // scales finger breadth and thickness
  // What a session runs with unless the experimenter chooses otherwise ("session"): where the
  // participant looks and what tracks their hand ("leap", "openxr", "scripted", "simulated";
  // empty: the front end's own default).
  SessionDisplay default_display = SessionDisplay::kWindow;
  std::string default_tracker;
  std::string text;  // the file's exact bytes

  std::vector<Condition> conditions() const;        // first factor varies slowest
  int factor_index(const std::string& name) const;  // -1 when absent
  // Whether the trials of `block` (1-based; 0, practice, never) ask the questionnaire, and
  // when it is asked in words ("after each trial of blocks 1 and 5").
  bool asks_questionnaire(int block) const;
  std::string questionnaire_schedule() const;
};

// Where a protocol's text comes from: a file for a new study, checked by today's rules, or
// a study database, which holds a protocol that was valid when the study was made (a cube of
// 2-200 mm, as handlab allowed before the 5-150 mm rule) and must still open.
enum class ProtocolSource { kNewStudy, kStoredStudy };

// Parses and validates; errors name the offending key.
Protocol parse_protocol(const std::string& text, const std::string& source_name,
                        ProtocolSource source = ProtocolSource::kNewStudy);
Protocol read_protocol(const std::string& path);

// One planned trial of a participant's schedule, in running order.
struct PlannedTrial {
  int position = 0;    // 0-based running order over the whole session
  int block = 0;       // 0 = practice, then 1..blocks
  int order = 0;       // 1-based place within its block
  int condition = 0;   // index into Protocol::conditions()
  int repetition = 0;  // how many times this condition has been run, this one included
  bool practice = false;
  bool questionnaire = false;
};

// The participant's whole schedule: practice trials, then the blocks. Reproducible from
// (protocol seed, participant id, enrolment index) on every platform.
std::vector<PlannedTrial> plan_schedule(const Protocol& protocol, const std::string& participant,
                                        int enrolment);

// Row `row` of a balanced (Williams) Latin square of n conditions: every condition follows
// every other equally often over n rows (2n for odd n).
std::vector<int> balanced_latin_square_row(int n, int row);

}  // namespace handlab::studies
