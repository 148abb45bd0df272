// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Running another program (private): found on PATH, started without a shell, its output
// caught in a file.

#include <string>
#include <vector>

namespace gencoord::deformable::detail {

/// The path of `program` on PATH (a name with a '/' is taken as it is), or "" when there is no
/// executable file of that name.
std::string find_program(const std::string& program);

/// How a program ended, and what it printed.
struct ProgramRun {
  int exit_code = -1;  ///< its exit status, -1 when a signal ended it
  int signal = 0;      ///< the signal that ended it, 0 when it exited
  std::string output;  ///< its standard output and error, interleaved

  bool succeeded() const { return exit_code == 0; }
  /// "exited with status 3" or "was ended by signal 6 (Aborted)".
  std::string status() const;
};

/// Runs the executable at `path` with `args` (argv[1...]; no shell, so arguments may hold
/// spaces), standard input from /dev/null, standard output and error into the file `log`,
/// which is read back into output. Through `stdbuf -o0` when stdbuf is on PATH, so that what a
/// program prints before it crashes is not lost in its buffer. \throws std::system_error when
/// the program cannot be started or waited for.
ProgramRun run_program(const std::string& path, const std::vector<std::string>& args,
                       const std::string& log);

}  // namespace gencoord::deformable::detail
