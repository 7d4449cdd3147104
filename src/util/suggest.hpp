// "Did you mean ...?" for a mistyped name: the candidate nearest in edit
// distance, when it is near enough to be what was meant.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace wp {

// Levenshtein distance: the fewest single-character insertions, deletions
// and substitutions that turn a into b.
std::size_t edit_distance(std::string_view a, std::string_view b);

// The candidate nearest to `typed`, if it is within a third of its length
// (at least 2 edits), so that "rendr" suggests "render" but "xyz" nothing.
std::optional<std::string> nearest_name(std::string_view typed,
                                        const std::vector<std::string>& candidates);

} // namespace wp
