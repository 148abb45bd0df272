// SPDX-License-Identifier: BSD-3-Clause
// bicycle_eigenvalues: the Whipple bicycle's (models/whipple_bicycle.py) stability in upright
// straight running, from the generated nonlinear model linearized at each speed.
//
//   bicycle_eigenvalues [--set name=value ...] [speed ...]
//
// Prints the four eigenvalues of roll and steer (1/s) at each speed given in m/s (by
// default 0 to 10 in steps of 1), then the weave speed (above it the oscillatory weave mode
// is stable) and the capsize speed (above it the capsize mode is unstable): the bicycle
// balances itself between them. --set changes a parameter of the model (w, c, lam, r_r, ...).
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "bicycle_stability.hpp"
#include "command_line.hpp"

namespace {

constexpr const char* kProgram = "bicycle_eigenvalues";

void print_eigenvalues(const gencoord::bicycle::Bicycle::Params& p, double speed) {
  std::printf("%6.3f", speed);
  for (const auto& value : gencoord::bicycle::eigenvalues(p, speed)) {
    if (value.imag() == 0.0) {
      std::printf("  %+.12f          ", value.real());
    } else {
      std::printf("  %+.12f %+.6fi", value.real(), value.imag());
    }
  }
  std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
  gencoord::bicycle::Bicycle::Params p;
  std::vector<double> speeds;
  for (int i = 1; i < argc; ++i) {
    const std::string argument = argv[i];
    if (argument == "--set") {
      const std::string setting = gencoord::drivers::option_value(kProgram, argc, argv, i);
      const auto equals = setting.find('=');
      double* slot = equals == std::string::npos ? nullptr : p.find(setting.substr(0, equals));
      if (!slot) {
        std::fprintf(stderr, "%s: error: --set takes name=value with a parameter of %s\n", kProgram,
                     gencoord::bicycle::Bicycle::name);
        return 2;
      }
      *slot = gencoord::drivers::parse_number(kProgram, setting.substr(equals + 1), "--set");
    } else if (argument == "--help" || argument == "-h") {
      std::printf("usage: %s [--set name=value ...] [speed ...]\n", kProgram);
      return 0;
    } else {
      speeds.push_back(gencoord::drivers::parse_number(kProgram, argument, "a speed"));
    }
  }
  if (speeds.empty())
    for (int k = 0; k <= 10; ++k) speeds.push_back(k);
  try {
    std::printf("upright straight running of %s: eigenvalues of roll and steer (1/s)\n",
                gencoord::bicycle::Bicycle::name);
    std::printf("v (m/s)\n");
    for (const double speed : speeds) print_eigenvalues(p, speed);
    const double weave = gencoord::bicycle::weave_speed(p);
    std::printf("weave speed    %.12f m/s\n", weave);
    std::printf("capsize speed  %.12f m/s\n", gencoord::bicycle::capsize_speed(p, weave));
  } catch (const std::exception& error) {
    std::fprintf(stderr, "%s: error: %s\n", kProgram, error.what());
    return 1;
  }
  return 0;
}
