// Running the octomotion command line from a test: its exit status and what it printed, and
// small readers for its text and CSV output.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace octomotion::test {

struct CliRun {
  int status;  // the exit code, -1 if the command did not exit normally
  std::string out, err;
};

inline std::string readText(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// `scratch` names the folder (under the temporary directory, made unique per process so ctest's
// parallel runs do not share it) that holds the captured output.
inline CliRun runCli(const std::string& args, const std::string& scratch) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / (scratch + "_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string out = (dir / "stdout").string(), err = (dir / "stderr").string();
  const int raw =
      std::system((std::string(OCTOMOTION_CLI) + " " + args + " >" + out + " 2>" + err).c_str());
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, readText(out), readText(err)};
}

inline std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream s(text);
  for (std::string l; std::getline(s, l);) out.push_back(l);
  return out;
}

// One CSV record: fields split at commas outside double quotes, quotes undone.
inline std::vector<std::string> csvFields(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
      fields.back() += '"';
      ++i;
    } else if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  return fields;
}

}  // namespace octomotion::test
