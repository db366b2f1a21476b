// dynamesh-cli end to end with typed surfaces (issue 8): bad formulas, options and base meshes
// end with exit status 2 and exactly one line on stderr; the shipped examples run.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace dynamesh {
namespace {

namespace fs = std::filesystem;

const std::string kCli = std::string(DYNAMESH_BINARY_DIR) + "/dynamesh-cli";
const std::string kSource = DYNAMESH_SOURCE_DIR;

struct CliResult {
  int status = -1;
  std::string out, err;
};

// Single-quoted for the shell. (Built with append: GCC 12 warns falsely, -Wrestrict, on
// "'" + s.)
std::string quoted(const std::string& arg) {
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

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

CliResult run_cli(const std::vector<std::string>& args) {
  const fs::path dir =
      fs::path(DYNAMESH_BINARY_DIR) / "test_scratch" / ("expr_cli_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::string command("cd ");
  command.append(quoted(kSource)).append(" && ").append(quoted(kCli)).append(" run");
  for (const std::string& a : args) command.append(" ").append(quoted(a));
  command.append(" > ").append(quoted((dir / "out").string()));
  command.append(" 2> ").append(quoted((dir / "err").string()));
  CliResult r;
  const int raw = std::system(command.c_str());
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = slurp(dir / "out");
  r.err = slurp(dir / "err");
  return r;
}

long lines(const std::string& text) {
  return std::count(text.begin(), text.end(), '\n');
}

TEST(ExprCli, BinaryIsBuilt) {
  // Every other test here runs it: a missing binary must fail, not skip.
  ASSERT_TRUE(fs::exists(kCli)) << kCli << " is missing: build the dynamesh-cli target";
}

TEST(ExprCli, BadInputExitsTwoWithOneLine) {
  ASSERT_TRUE(fs::exists(kCli)) << kCli;
  const std::string box = "-1,-1,-1,1,1,1";
  struct Case {
    std::vector<std::string> args;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {{"--implicit", "x^2 + * y", "--bounds", box}, "implicit formula 'x^2 + * y'"},
      {{"--implicit", "x^2 + w^2", "--bounds", box}, "unknown name 'w'"},
      {{"--implicit", "sqrt(0.5 - x) - 0.3", "--bounds", box}, "is NaN at"},
      {{"--implicit", "x^2+y^2+z^2-0.5", "--bounds", "-1,-1,-1,1,1,-1"}, "is empty along z"},
      {{"--implicit", "x^2+y^2+z^2+1", "--bounds", box}, "no zero crossing"},
      {{"--implicit", "x^2+y^2+z^2-0.5"}, "--implicit needs --bounds"},
      {{"--height", "log(x)"}, "is not finite"},
      {{"--parametric", "cos(u);v", "--domain", "0,1,0,1"}, "three formulas"},
      {{"--implicit", "x^2+y^2+z^2-0.5", "--bounds", box, "--base-mesh", "no/such.obj"},
       "no such file"},
      {{"--implicit", "x^2+y^2+z^2-0.5", "--bounds", box, "--base-mesh",
        "assets/examples/README.md"},
       "use a .obj or .ply"},
  };
  for (const Case& c : cases) {
    std::vector<std::string> args{"--scene", "expr", "--quiet"};
    args.insert(args.end(), c.args.begin(), c.args.end());
    const CliResult r = run_cli(args);
    EXPECT_EQ(r.status, 2) << c.expected << "; stderr: " << r.err;
    EXPECT_EQ(lines(r.err), 1) << "stderr: " << r.err;
    EXPECT_EQ(r.err.rfind("dynamesh-cli: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(c.expected), std::string::npos) << "stderr: " << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
}

TEST(ExprCli, ExamplesRun) {
  ASSERT_TRUE(fs::exists(kCli)) << kCli;
  int examples = 0;
  for (const auto& entry : fs::directory_iterator(kSource + "/assets/examples")) {
    if (entry.path().extension() != ".args") continue;
    ++examples;
    std::vector<std::string> args;
    std::ifstream in(entry.path());
    for (std::string line; std::getline(in, line);)
      if (!line.empty()) args.push_back(line);
    // Coarse and short: this checks that the example parses, builds and steps.
    for (const char* a : {"--threshold", "0.03", "--steps", "2", "--quiet"}) args.push_back(a);
    const CliResult r = run_cli(args);
    EXPECT_EQ(r.status, 0) << entry.path() << ": " << r.err;
    EXPECT_NE(r.out.find("\"triangles\""), std::string::npos) << entry.path() << ": " << r.out;
  }
  EXPECT_GE(examples, 4);
}

}  // namespace
}  // namespace dynamesh
