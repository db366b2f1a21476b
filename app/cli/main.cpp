// dynamesh-cli: the batch command line. Bad input: one line on stderr, exit status 2.
#include <cstdlib>
#include <iostream>
#include <new>
#include <string>
#include <vector>

#include "app/cli/run_command.h"
#include "app/cli/run_options.h"
#include "core/io/atomic_file.h"
#include "core/parallel.h"
#include "core/surface/scene_registry.h"

namespace {

// One short line, whatever the message quotes from the command line (a scene name or file
// name with a newline in it: control characters are shown escaped; a huge formula: cut).
std::string one_line(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '\n')
      out += "\\n";
    else if (c == '\r')
      out += "\\r";
    else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      out += '?';
    else
      out += c;
  }
  // A message quoting a 100,000-character formula or header line is one line but not a
  // readable one: its middle is left out.
  constexpr std::size_t kHead = 400, kTail = 200;
  if (out.size() > kHead + kTail + 100)
    out = out.substr(0, kHead) + " [... " + std::to_string(out.size() - kHead - kTail) +
          " characters left out ...] " + out.substr(out.size() - kTail);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace dynamesh;
  const std::vector<std::string> args(argv + 1, argv + argc);
  // Ctrl-C, SIGTERM, SIGHUP, SIGPIPE: no *.partial file stays; complete frames do (README).
  remove_partial_files_on_signal();
  try {
    if (!args.empty() && args[0] == "--version") {
      // What libgomp read at start-up: the environment, which the engine's own start may have
      // completed (core/parallel.h).
      const char* policy = std::getenv("OMP_WAIT_POLICY");
      std::cout << "dynamesh-cli " << DYNAMESH_VERSION << "\n"
                << "OpenMP threads: " << omp_get_max_threads()
                << ", wait policy: " << engine_wait_policy()
                << " (OMP_WAIT_POLICY=" << (policy ? policy : "unset") << ")\n";
      return 0;
    }
    if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
      std::cout << main_help();
      return args.empty() ? 2 : 0;
    }
    if (args[0] == "scenes") {
      std::cout << scene_help();
      return 0;
    }
    if (args[0] != "run")
      throw UsageError("unknown command '" + args[0] + "' (try: dynamesh-cli run --help)");
    const std::vector<std::string> rest(args.begin() + 1, args.end());
    for (const std::string& a : rest)
      if (a == "--help" || a == "-h") {
        std::cout << run_help();
        return 0;
      }
    return run_command(parse_run_options(rest), std::cout, std::cerr);
  } catch (const UsageError& e) {
    std::cerr << "dynamesh-cli: " << one_line(e.what()) << "\n";
    return 2;
  } catch (const std::bad_alloc&) {
    std::cerr << "dynamesh-cli: out of memory: lower --max-triangles, --max-samples or "
                 "--density (the budgets' estimate is checked against --max-memory)\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "dynamesh-cli: error: " << one_line(e.what()) << "\n";
    return 1;
  }
}
