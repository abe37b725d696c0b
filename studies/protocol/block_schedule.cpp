#include "studies/protocol/block_schedule.h"

#include <numeric>
#include <stdexcept>

#include "core/util/portable_random.h"

namespace handlab::studies {

BlockSchedule randomized_block_schedule(std::uint64_t study_seed, std::string_view participant_id,
                                        int conditions, int blocks) {
  if (conditions < 1 || blocks < 1)
    throw std::invalid_argument("a schedule needs at least one condition and one block");
  util::PortableRandom random(study_seed ^ util::fnv1a64(participant_id));
  BlockSchedule schedule(static_cast<std::size_t>(blocks));
  for (auto& order : schedule) {
    order.resize(static_cast<std::size_t>(conditions));
    std::iota(order.begin(), order.end(), 0);
    random.shuffle(order);
  }
  return schedule;
}

}  // namespace handlab::studies
