// cli.h: the command line every offline tool (tools/*.cpp) shares. It is header-only so that the tools' glob in
// CMakeLists.txt, which makes an executable of each tools/*.cpp, leaves it alone; a tool includes it as "cli.h".
//   wantsHelp(argc, argv)        true when any argument is -h or --help: the tool then prints its help and exits 0.
//   printHelp(usage, body)       prints "usage: USAGE" and BODY to stdout; returns 0. BODY is a raw string literal
//                                whose text starts on the line after its R"( so it begins with a line break.
//   badArgument(usage, argc, argv, i)  why argv[i], which the parser did not take, is wrong: an option of USAGE
//                                given last without its value ("--out needs a value"), or an unknown argument.
//   fail(tool, usage, why)       prints "TOOL: WHY", "usage: USAGE" and where the help is to stderr; returns 2, the
//                                tools' exit code for bad arguments.
// USAGE is the tool's usage line without "usage: "; a tool with several forms puts each further form on a line of
// its own, indented by 7 spaces so that it lines up under the first.
#pragma once

#include <cstdio>
#include <cstring>
#include <string>

namespace tow_sim::cli
{
inline bool wantsHelp(int argc, char** argv)
{
  for (int i = 1; i < argc; ++i)
    if (!std::strcmp(argv[i], "-h") || !std::strcmp(argv[i], "--help"))
      return true;
  return false;
}

inline int printHelp(const char* usage, const char* body)
{
  std::printf("usage: %s\n%s", usage, body);
  return 0;
}

inline std::string badArgument(const char* usage, int argc, char** argv, int i)
{
  const std::string arg = argv[i];
  if (i + 1 == argc && arg.rfind("--", 0) == 0 && std::strstr(usage, (arg + " ").c_str()))
    return arg + " needs a value";
  return "unknown argument '" + arg + "'";
}

inline int fail(const char* tool, const char* usage, const std::string& why)
{
  std::fprintf(stderr, "%s: %s\nusage: %s\nRun '%s --help' for what each option means.\n", tool, why.c_str(), usage,
               tool);
  return 2;
}
}  // namespace tow_sim::cli
