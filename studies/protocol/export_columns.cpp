#include "studies/protocol/export_columns.h"

#include <algorithm>

namespace handlab::studies {

std::vector<std::string> fixed_export_columns() {
  std::vector<std::string> columns;
  auto add = [&](auto& list) {
    for (const char* c : list)
      if (std::find(columns.begin(), columns.end(), c) == columns.end()) columns.push_back(c);
  };
  add(kParticipantColumns);
  add(kDesignColumns);
  add(kTrialColumns);
  add(kFrameColumns);
  return columns;
}

}  // namespace handlab::studies
