// Runs the real dynamesh-cli for end-to-end tests: the arguments are quoted for the shell,
// stdout and stderr are captured, and a successful run's closing JSON line is parsed.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace dynamesh::test {

using Args = std::vector<std::string>;

// Options joined: scene(...) + Args{"--threshold", "0.002"}. (Bring it in with
// `using test::operator+;`: the arguments' namespace is std.)
inline Args operator+(Args a, const Args& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

inline const std::string& cli_path() {
  static const std::string path = std::string(DYNAMESH_BINARY_DIR) + "/dynamesh-cli";
  return path;
}

// Single-quoted for the shell (appended piecewise: GCC 12 warns falsely on "'" + s).
inline std::string shell_quoted(const std::string& arg) {
  std::string q(1, '\'');
  for (char c : arg) {
    if (c == '\'')
      q.append("'\\''");
    else
      q.push_back(c);
  }
  q.push_back('\'');
  return q;
}

inline std::string slurp_file(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The run's JSON summary: the last line of stdout that starts with '{' (the summary is one
// line; a JSON object within it, as each of `topology_events`, or a CSV on stdout before it,
// must not be taken for it). A discarded value when there is none or it does not parse.
inline nlohmann::json summary_json(const std::string& out) {
  std::size_t end = out.size();
  while (end > 0) {
    const std::size_t newline = out.rfind('\n', end - 1);
    const std::size_t start = newline == std::string::npos ? 0 : newline + 1;
    if (start < end && out[start] == '{')
      return nlohmann::json::parse(out.substr(start, end - start), nullptr, false);
    if (newline == std::string::npos) break;
    end = newline;
  }
  return nlohmann::json(nlohmann::json::value_t::discarded);
}

struct CliRun {
  int status = -1;
  std::string out, err;
  nlohmann::json json;  // the last line of stdout, when the run succeeded

  // A number of the JSON summary (fails the test, returns NaN, when absent).
  double operator[](const char* key) const {
    if (!json.contains(key) || !json[key].is_number()) {
      ADD_FAILURE() << "no number '" << key << "' in " << out;
      return std::nan("");
    }
    return json[key].get<double>();
  }
};

// A per-process scratch directory under the build tree.
inline std::filesystem::path cli_scratch(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(DYNAMESH_BINARY_DIR) / "test_scratch" /
                                    (name + "_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir;
}

// `dynamesh-cli run ARGS...`; `redirect` replaces the default capture of stdout (e.g. to
// test what the program does with /dev/stdout itself).
inline CliRun run_cli(const std::vector<std::string>& args, const std::string& command = "run") {
  static int serial = 0;
  const std::filesystem::path dir = cli_scratch("cli_runner");
  const std::string stem = (dir / std::to_string(serial++)).string();
  std::string line = shell_quoted(cli_path()) + " " + command;
  for (const std::string& a : args) line.append(" ").append(shell_quoted(a));
  line.append(" > ").append(shell_quoted(stem + ".out"));
  line.append(" 2> ").append(shell_quoted(stem + ".err"));
  CliRun r;
  const int raw = std::system(line.c_str());
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = slurp_file(stem + ".out");
  r.err = slurp_file(stem + ".err");
  if (r.status == 0) r.json = summary_json(r.out);
  return r;
}

}  // namespace dynamesh::test
