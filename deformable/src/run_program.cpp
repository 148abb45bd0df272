// SPDX-License-Identifier: BSD-3-Clause
// Runs a program with posix_spawn, its output redirected to a file, and waits for it.
#include "run_program.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <system_error>

extern char** environ;

namespace gencoord::deformable::detail {

namespace {

bool is_executable_file(const std::string& path) {
  struct stat info;
  return ::stat(path.c_str(), &info) == 0 && S_ISREG(info.st_mode) &&
         ::access(path.c_str(), X_OK) == 0;
}

// Closes the file actions however the spawn goes.
struct FileActions {
  posix_spawn_file_actions_t actions;
  FileActions() { posix_spawn_file_actions_init(&actions); }
  ~FileActions() { posix_spawn_file_actions_destroy(&actions); }
  FileActions(const FileActions&) = delete;
  FileActions& operator=(const FileActions&) = delete;
};

}  // namespace

std::string find_program(const std::string& program) {
  if (program.find('/') != std::string::npos) return is_executable_file(program) ? program : "";
  const char* path = std::getenv("PATH");
  const std::string dirs = path != nullptr ? path : "/usr/local/bin:/usr/bin:/bin";
  for (size_t at = 0;;) {
    const size_t colon = dirs.find(':', at);
    std::string dir = dirs.substr(at, colon - at);
    if (dir.empty()) dir = ".";  // an empty entry is the working directory
    const std::string candidate = dir + "/" + program;
    if (is_executable_file(candidate)) return candidate;
    if (colon == std::string::npos) return "";
    at = colon + 1;
  }
}

std::string ProgramRun::status() const {
  if (signal != 0) {
    return "was ended by signal " + std::to_string(signal) + " (" + strsignal(signal) + ")";
  }
  return "exited with status " + std::to_string(exit_code);
}

ProgramRun run_program(const std::string& path, const std::vector<std::string>& args,
                       const std::string& log) {
  std::vector<std::string> command;
  const std::string stdbuf = find_program("stdbuf");
  if (!stdbuf.empty()) command = {stdbuf, "-o0"};
  command.push_back(path);
  command.insert(command.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& word : command) argv.push_back(word.data());
  argv.push_back(nullptr);

  FileActions files;
  int error = posix_spawn_file_actions_addopen(&files.actions, 0, "/dev/null", O_RDONLY, 0);
  if (error == 0) {
    error = posix_spawn_file_actions_addopen(&files.actions, 1, log.c_str(),
                                             O_WRONLY | O_CREAT | O_TRUNC, 0600);
  }
  if (error == 0) error = posix_spawn_file_actions_adddup2(&files.actions, 1, 2);
  pid_t pid = 0;
  if (error == 0) error = posix_spawn(&pid, argv[0], &files.actions, nullptr, argv.data(), environ);
  if (error != 0) {
    throw std::system_error(error, std::generic_category(), "cannot start " + command[0]);
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) {
      throw std::system_error(errno, std::generic_category(), "cannot wait for " + path);
    }
  }

  ProgramRun run;
  if (WIFEXITED(status)) {
    run.exit_code = WEXITSTATUS(status);
  } else if (WIFSIGNALED(status)) {
    run.signal = WTERMSIG(status);
  }
  std::ifstream in(log);
  std::ostringstream text;
  text << in.rdbuf();
  run.output = text.str();
  return run;
}

}  // namespace gencoord::deformable::detail
