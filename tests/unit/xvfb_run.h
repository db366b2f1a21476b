// The real viewer (or a script driving it with xdotool) under a fresh virtual display, for the
// tests that judge what a user would see: xvfb-run from Debian's xvfb, whose package is in
// scripts/debian-packages.txt, so these tests fail rather than skip where it is missing.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "test_render_scratch.h"

namespace dynamesh::test {

// Whether `program` is on PATH (the viewer tests need xvfb-run; one needs ffprobe).
inline bool on_path(const std::string& program) {
  return std::system(("command -v " + program + " >/dev/null 2>&1").c_str()) == 0;
}

inline constexpr const char* kXvfbMissing = "xvfb-run not found: install the Debian package xvfb";

struct XvfbOptions {
  std::string screen = "1280x800x24";  // the virtual screen, WxHxDepth
  int kill_after_seconds = 0;          // > 0: `timeout -s KILL` ends a hang (status 137)
};

struct XvfbRun {
  int status = -1;     // the command's exit status; -1 when a signal ended it
  std::string output;  // its stdout and stderr, as written to the log
};

// Runs the shell command line `command` with its stdout and stderr going to `log`.
inline XvfbRun run_logged(const std::string& command, const std::filesystem::path& log) {
  const int raw = std::system((command + " > '" + log.string() + "' 2>&1").c_str());
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, slurp_text(log)};
}

// Runs the shell command line `command` under its own display; its output goes to `log`.
inline XvfbRun run_under_xvfb(const std::string& command, const std::filesystem::path& log,
                              const XvfbOptions& options = {}) {
  const std::string timeout =
      options.kill_after_seconds > 0
          ? "timeout -s KILL " + std::to_string(options.kill_after_seconds) + " "
          : "";
  // The X authority file beside the log, not in a directory xvfb-run makes and removes: under
  // load its removal failed now and then ("problem while cleaning up temporary directory",
  // status 5, whatever the viewer's own status).
  const std::string auth = log.string() + ".xauth";
  return run_logged(
      timeout + "xvfb-run -a -f '" + auth + "' -s '-screen 0 " + options.screen + "' " + command,
      log);
}

// A shell script under its own display (the scripted-input tests).
inline XvfbRun run_script_under_xvfb(const std::filesystem::path& script,
                                     const std::filesystem::path& log,
                                     const XvfbOptions& options = {}) {
  return run_under_xvfb("sh '" + script.string() + "'", log, options);
}

// The viewer's command line with `options`. (Appended piece by piece: GCC 12 reports a false
// -Wrestrict for "'" + std::string(...) once this is inlined.)
inline std::string viewer_command(const std::string& options) {
  std::string command = "'";
  command += DYNAMESH_VIEWER;
  command += "' ";
  command += options;
  return command;
}

}  // namespace dynamesh::test
