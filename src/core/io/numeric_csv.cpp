#include "tow_sim/core/io/numeric_csv.h"

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace tow_sim
{
namespace
{
std::string trimmed(const std::string& s)
{
  const size_t a = s.find_first_not_of(" \t\r"), b = s.find_last_not_of(" \t\r");
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}
}  // namespace

bool parseFiniteNumber(const std::string& text, double& value)
{
  size_t used = 0;
  try
  {
    value = std::stod(text, &used);
  }
  catch (const std::exception&)
  {
    return false;
  }
  return used != 0 && used == text.size() && std::isfinite(value);
}

std::vector<NumericCsvRow> readNumericCsv(const std::string& path, int columns, const std::string& what,
                                          const std::string& column_names)
{
  const std::string name = what + " '" + path + "'";
  std::ifstream in(path);
  if (!in)
    throw std::invalid_argument(name + ": cannot be read");
  std::vector<NumericCsvRow> rows;
  std::string line;
  int number = 0;
  bool header = true;
  while (std::getline(in, line))
  {
    ++number;
    const std::string t = trimmed(line);
    if (t.empty() || t[0] == '#')
      continue;
    if (header)
    {
      header = false;
      continue;
    }
    const std::string at = name + " line " + std::to_string(number) + ": ";
    NumericCsvRow row;
    row.line = number;
    std::stringstream cells(t);
    std::string cell;
    while (std::getline(cells, cell, ','))
    {
      const std::string c = trimmed(cell);
      double value = NAN;
      if (!parseFiniteNumber(c, value))
        throw std::invalid_argument(at + "'" + c + "' is not a finite number");
      row.values.push_back(value);
    }
    if (static_cast<int>(row.values.size()) != columns)
      throw std::invalid_argument(at + "needs " + std::to_string(columns) + " columns (" + column_names + "), got " +
                                  std::to_string(row.values.size()));
    rows.push_back(std::move(row));
  }
  return rows;
}

}  // namespace tow_sim
