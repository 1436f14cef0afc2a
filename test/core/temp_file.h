// A file written for a test in the system's temporary folder.
#pragma once

#include <string>

namespace test
{
// Writes `text` to <temp>/<name> and returns the path.
std::string writeTempFile(const std::string& name, const std::string& text);
}  // namespace test
