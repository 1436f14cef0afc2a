#include "tow_sim/core/io/measurement_csv.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "tow_sim/core/io/numeric_csv.h"

namespace tow_sim
{
namespace
{
std::vector<std::string> splitCells(const std::string& line)
{
  std::vector<std::string> cells;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, ','))
    cells.push_back(cell);
  if (!line.empty() && line.back() == ',')
    cells.emplace_back();
  for (std::string& c : cells)  // trim spaces and a Windows line end
  {
    const size_t a = c.find_first_not_of(" \t\r"), b = c.find_last_not_of(" \t\r");
    c = a == std::string::npos ? "" : c.substr(a, b - a + 1);
  }
  return cells;
}

// The header's columns as field indices of SurveyMeasurement::fields().
std::vector<int> columnsOf(const std::vector<std::string>& names, const std::string& where)
{
  const std::vector<std::string> known = splitCells(surveyMeasurementHeader());
  std::vector<int> columns;
  for (const std::string& name : names)
  {
    int index = -1;
    for (size_t k = 0; k < known.size(); ++k)
      if (known[k] == name)
        index = static_cast<int>(k);
    for (int c : columns)
      if (index >= 0 && c == index)
        throw std::invalid_argument(where + ": column '" + name + "' appears twice");
    if (index < 0)
      throw std::invalid_argument(where + ": unknown column '" + name + "'; the columns are " +
                                  surveyMeasurementHeader());
    columns.push_back(index);
  }
  if (columns.empty() || std::find(columns.begin(), columns.end(), 0) == columns.end())
    throw std::invalid_argument(
        where + ": the header must name a column t (and the measurements': " + surveyMeasurementHeader() + ")");
  return columns;
}

}  // namespace

std::vector<SurveyMeasurement> readSurveyMeasurements(const std::string& path)
{
  std::ifstream in(path);
  if (!in)
    throw std::invalid_argument("measurements '" + path + "': cannot read the file");
  std::vector<SurveyMeasurement> rows;
  std::vector<int> columns;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number)
  {
    const std::string where = "measurements '" + path + "' line " + std::to_string(number);
    if (line.find_first_not_of(" \t\r") == std::string::npos || line[line.find_first_not_of(" \t")] == '#')
      continue;
    const std::vector<std::string> cells = splitCells(line);
    if (columns.empty())
    {
      columns = columnsOf(cells, where);
      continue;
    }
    if (cells.size() != columns.size())
      throw std::invalid_argument(where + ": " + std::to_string(cells.size()) + " cells; the header has " +
                                  std::to_string(columns.size()));
    SurveyMeasurement m;
    const std::array<double*, SurveyMeasurement::kColumns> fields = m.fields();
    for (size_t c = 0; c < cells.size(); ++c)
      if (!cells[c].empty() && !parseFiniteNumber(cells[c], *fields[columns[c]]))
        throw std::invalid_argument(where + ": column " + splitCells(surveyMeasurementHeader())[columns[c]] + " '" +
                                    cells[c] + "' is not a finite number (an empty cell: no measurement)");
    if (std::isnan(m.t) || cells[std::find(columns.begin(), columns.end(), 0) - columns.begin()].empty())
      throw std::invalid_argument(where + ": column t must hold the row's time [s]");
    rows.push_back(m);
  }
  if (columns.empty())
    throw std::invalid_argument("measurements '" + path + "': no header line");
  return rows;
}

}  // namespace tow_sim
