// SPDX-License-Identifier: BSD-3-Clause
// Command-line helpers shared by the drivers and the example programs: numbers and option
// values, with errors that name the program and the option and exit with status 2.
#pragma once

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace gencoord::drivers {

/// `text` as a finite number; otherwise prints "<program>: error: <what> expects a number"
/// and exits with status 2.
inline double parse_number(const char* program, const std::string& text, const std::string& what) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(value)) {
    std::cerr << program << ": error: " << what << " expects a number, got '" << text << "'\n";
    std::exit(2);
  }
  return value;
}

/// Comma-separated numbers (`1,2.5,-3`), each as parse_number().
inline std::vector<double> parse_list(const char* program, const std::string& text,
                                      const std::string& what) {
  std::vector<double> values;
  std::stringstream stream(text);
  for (std::string item; std::getline(stream, item, ',');)
    values.push_back(parse_number(program, item, what));
  return values;
}

/// The value of option argv[i], advancing i past it; exits with status 2 when it is missing.
inline std::string option_value(const char* program, int argc, char** argv, int& i) {
  if (i + 1 >= argc) {
    std::cerr << program << ": error: " << argv[i] << " needs a value\n";
    std::exit(2);
  }
  return argv[++i];
}

}  // namespace gencoord::drivers
