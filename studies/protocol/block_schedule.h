// The order in which a participant meets the conditions: each block holds every condition
// once, in an order drawn per block and per participant from a seeded generator.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

namespace handlab::studies {

// orders[b][k] is the index of the condition run k-th in block b.
using BlockSchedule = std::vector<std::vector<int>>;

// Same (seed, participant, conditions, blocks) → same schedule, on every platform.
BlockSchedule randomized_block_schedule(std::uint64_t study_seed, std::string_view participant_id,
                                        int conditions, int blocks);

}  // namespace handlab::studies
