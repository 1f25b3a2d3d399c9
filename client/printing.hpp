// How flagctl shows what the server says: the parameter table, status, a state line, the timeline.
#pragma once

#include <ostream>
#include <string>

#include "flagsim/params_t.hpp"
#include "flagsim/state_t.hpp"
#include "flagsim/status_t.hpp"
#include "flagsim/timeline_t.hpp"

namespace flagsim {

/// One row per parameter: name, current value, unit, allowed range, default, description.
void PrintParams(const params_t& params, std::ostream& out);

/// One "key: value" line per field.
void PrintStatus(const status_t& status, std::ostream& out);

/// The play state, then one row per key: time, law, and what it sets (wind, camera, parameters).
void PrintTimeline(const timeline_t& timeline, std::ostream& out);

/// The flag's fly-end top corner (the node farthest from the pole on row 0), m.
std::string TipText(const state_t& state);

}  // namespace flagsim
