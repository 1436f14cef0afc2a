// A run's saved state as a text file (tow_sim_node's ~save_state and ~load_state, the batch's save_state
// and initial_state: {type: file}): one line per field, `key value ...`, the numbers with 17 significant
// digits so that reading gives the very same doubles back. docs/nodes.md, "Saved states".
#pragma once

#include <map>
#include <string>

#include "tow_sim/core/run/tow_run.h"

namespace tow_sim
{
// The text of a state, and the state of a text. Format 2 adds the configuration (RunState::configuration:
// `config.KEY VALUE` lines and `config_hash`, a 64-bit FNV-1a of them, in hexadecimal); format 1 is still
// read (no configuration). Reading throws std::invalid_argument naming `source` and the line or key: not a
// tow_sim state (or another format version), a key unknown, missing or given twice, a wrong count of values,
// a value that is not a number, or a configuration that does not match its hash.
std::string runStateText(const RunState& state);
RunState parseRunState(const std::string& text, const std::string& source);

// The same to and from a file (std::runtime_error when it cannot be written or read).
void writeRunState(const std::string& path, const RunState& state);
// The 64-bit FNV-1a hash of a configuration's "key=value\n" lines (in key order), 16 hexadecimal digits.
std::string configurationHash(const std::map<std::string, std::string>& configuration);
RunState readRunState(const std::string& path);

}  // namespace tow_sim
