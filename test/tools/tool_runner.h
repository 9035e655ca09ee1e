// Running a command-line tool as a user would, for the tools' smoke tests: its exit code, its
// output, and the key=value pairs of the RESULT line it must end with.
#ifndef HEX_SLAM_TEST_TOOLS_TOOL_RUNNER_H_
#define HEX_SLAM_TEST_TOOLS_TOOL_RUNNER_H_

#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

namespace hex_slam {
namespace test {

struct ToolRun {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

inline ToolRun RunTool(const std::string& command) {
  ToolRun run;
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return run;
  char buffer[4096];
  while (std::fgets(buffer, sizeof(buffer), pipe)) run.output += buffer;
  const int status = ::pclose(pipe);
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

// Parses the last non-empty line, which must be "RESULT key=value ..."; empty otherwise.
inline std::map<std::string, double> ResultLine(const std::string& output) {
  std::map<std::string, double> values;
  std::istringstream lines(output);
  std::string line, last;
  while (std::getline(lines, line)) {
    if (!line.empty()) last = line;
  }
  std::istringstream fields(last);
  std::string word;
  fields >> word;
  if (word != "RESULT") return values;
  while (fields >> word) {
    const std::size_t eq = word.find('=');
    if (eq != std::string::npos) values[word.substr(0, eq)] = std::atof(word.c_str() + eq + 1);
  }
  return values;
}

inline bool FileNonEmpty(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  return in && in.tellg() > 0;
}

}  // namespace test
}  // namespace hex_slam

#endif  // HEX_SLAM_TEST_TOOLS_TOOL_RUNNER_H_
