#include "core/io/dicom_series.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

extern char** environ;

namespace dynamesh {
namespace {

constexpr const char* kConverter = "dcm2niix";

// Runs argv[0] (looked up in PATH) with stdout and stderr into `log`; returns the exit
// status, or -1 when it could not be started. No shell: the folder name is passed as is.
int run_quietly(const std::vector<std::string>& args, const std::filesystem::path& log) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) return -1;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return -1;
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

ConvertedDicomSeries::ConvertedDicomSeries(const std::filesystem::path& folder) {
  namespace fs = std::filesystem;
  std::string pattern = (fs::temp_directory_path() / "dynamesh-dicom-XXXXXX").string();
  if (!mkdtemp(pattern.data()))
    throw std::runtime_error("cannot create a temporary directory for the DICOM conversion");
  temporary_ = pattern;
  const fs::path out = temporary_ / "out";
  fs::create_directory(out);
  // -z n: plain .nii; -b n: no JSON sidecar; -f: a fixed name; -d 0: only this
  // folder, not its subfolders (a series is one folder).
  const int status = run_quietly({kConverter, "-z", "n", "-b", "n", "-d", "0", "-f", "volume", "-o",
                                  out.string(), folder.string()},
                                 temporary_ / "dcm2niix.log");
  std::vector<fs::path> volumes;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(out, ec))
    if (e.path().extension() == ".nii") volumes.push_back(e.path());
  if (status == -1) {
    fs::remove_all(temporary_, ec);
    throw std::runtime_error(std::string("a DICOM folder needs ") + kConverter +
                             ", which could not be run; install the Debian package dcm2niix");
  }
  if (status != 0 || volumes.empty()) {
    fs::remove_all(temporary_, ec);
    throw std::runtime_error("'" + folder.string() + "' holds no DICOM series that " + kConverter +
                             " could convert (exit status " + std::to_string(status) + ")");
  }
  if (volumes.size() > 1) {
    fs::remove_all(temporary_, ec);
    throw std::runtime_error("'" + folder.string() + "' holds " + std::to_string(volumes.size()) +
                             " DICOM series or echoes; point --volume at a folder with one");
  }
  nifti_ = volumes.front();
}

ConvertedDicomSeries::~ConvertedDicomSeries() {
  std::error_code ignored;
  std::filesystem::remove_all(temporary_, ignored);
}

}  // namespace dynamesh
