// A small reader for the numeric CSV files the configuration names (RAO tables, measured ship motion).
#pragma once

#include <string>
#include <vector>

namespace tow_sim
{
struct NumericCsvRow
{
  int line = 0;                // 1-based line number in the file
  std::vector<double> values;  // exactly `columns` finite numbers
};

// The whole of `text` as a finite number (no trailing characters); false otherwise, `value` then unset.
bool parseFiniteNumber(const std::string& text, double& value);

// Reads `path`: blank lines and lines starting with # are skipped, the first other line is a header (not
// checked), every further line holds `columns` comma-separated finite numbers. Throws
// std::invalid_argument naming `what`, the file and the line ("rao file 'x.csv' line 7: ...").
std::vector<NumericCsvRow> readNumericCsv(const std::string& path, int columns, const std::string& what,
                                          const std::string& column_names);

}  // namespace tow_sim
