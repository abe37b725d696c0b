// How a strategy level retargets: the method the pipeline runs and its parameters, kept apart
// from the level's name, a label for people that nothing in the pipeline reads. In a protocol:
//   {"name": "A", "method": "naive"}
//   {"name": "B", "method": "ours", "parameters": {"tip_weights": [4, 4, 1, 1, 1]}}
// A level without "method" named "naive" or "ours" (protocols before methods) runs that method.
#pragma once

#include <string>

#include "core/retarget/retargeter.h"
#include "core/util/json_value.h"
#include "studies/protocol/protocol_reader.h"

namespace handlab::studies {

struct StrategyMethod {
  retarget::Strategy method = retarget::Strategy::kOurs;
  retarget::OursOptions ours;  // Ours' parameters; Naive takes none
};

// A strategy level's method and parameters; `where` names the level in errors.
StrategyMethod read_strategy_method(const ProtocolReader& reader, const util::JsonValue& level,
                                    const std::string& where);

// The method in words, with the parameters that differ from its defaults:
// "naive", "ours", "ours (tip weights 1, 1, 1, 1, 1)".
std::string describe(const StrategyMethod& method);

}  // namespace handlab::studies
