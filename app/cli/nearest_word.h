// The word a user probably meant: for a hint after a misspelt option or value.
#pragma once

#include <string>
#include <vector>

namespace handlab::cli {

// The candidate within two edits (insertions, deletions, substitutions, transpositions) of
// `typed`, the closest first; empty when none is that close.
std::string nearest_word(const std::string& typed, const std::vector<std::string>& candidates);

// " (did you mean X?)" for the nearest candidate, or "".
std::string did_you_mean(const std::string& typed, const std::vector<std::string>& candidates,
                         const std::string& prefix = {});

}  // namespace handlab::cli
