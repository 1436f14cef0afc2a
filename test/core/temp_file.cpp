#include "core/temp_file.h"

#include <filesystem>
#include <fstream>

namespace test
{
std::string writeTempFile(const std::string& name, const std::string& text)
{
  const std::string path = (std::filesystem::temp_directory_path() / name).string();
  std::ofstream(path) << text;
  return path;
}
}  // namespace test
