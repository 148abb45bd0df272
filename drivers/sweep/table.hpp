// SPDX-License-Identifier: BSD-3-Clause
// The sample table that `gencoord sweep` writes (python/gencoord/sweep/table.py): settings as `key
// value` lines, then `samples N` and N rows of values. Rank 0 reads the file; the other ranks get
// its settings from rank 0 (the header: every line up to `samples N`) and each chunk's rows
// with the chunk, so that they need neither the file nor memory for all the samples.
#pragma once

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace gencoord::sweep {

/// One comparison of the event condition: [abs](quantity) op value.
struct EventClause {
  std::string kind;        // q, v or energy
  std::string coordinate;  // for q and v
  bool absolute = false;
  std::string op;  // >, >=, <, <=
  double value = 0.0;
};

/// A sampled variable: what it sets (q, v or parameters) and its name.
struct Column {
  std::string kind, name;
  std::string label() const { return kind + "." + name; }
};

struct Table {
  std::string path;
  std::string digest, build, model, integrator, method;
  double dt = 0.0, t_end = 0.0;
  long long steps = 0, chunk = 0, seed = -1, trajectory_every = 0;
  bool record_final_state = false, record_energy_drift = false, record_event_time = false;
  bool has_event = false, event_stop = true;
  std::string event_text, sweep_file;
  std::vector<EventClause> clauses;
  std::vector<std::pair<std::string, double>> parameters;  // fixed values
  struct Initial {
    std::string kind, name;
    double value;
  };
  std::vector<Initial> initial;
  std::vector<long long> grid_points;
  std::vector<std::string> sweep_lines, banner_lines;
  std::vector<Column> columns;
  long long samples = 0;
  std::vector<double> values;  // samples x columns, row by row

  long long chunks() const { return samples / chunk + (samples % chunk != 0); }  // no overflow
  long long chunk_begin(long long c) const { return c * chunk; }
  long long chunk_size(long long c) const { return std::min(chunk, samples - chunk_begin(c)); }
  /// Recorded trajectory points: steps 0, every, 2 every, ... up to `steps`.
  long long trajectory_points() const {
    return trajectory_every > 0 ? steps / trajectory_every + 1 : 0;
  }
  const double* row(long long sample) const {
    return values.data() + sample * static_cast<long long>(columns.size());
  }
};

class TableError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

namespace detail {

inline double table_number(const std::string& path, int line, const std::string& text) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0')
    throw TableError(path + ":" + std::to_string(line) + ": not a number: '" + text + "'");
  return value;
}

inline long long table_integer(const std::string& path, int line, const std::string& text) {
  char* end = nullptr;
  const long long value = std::strtoll(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0')
    throw TableError(path + ":" + std::to_string(line) + ": not a whole number: '" + text + "'");
  return value;
}

}  // namespace detail

/// The table in `text` (of the file `path`): the settings, and with `values` the samples'
/// values too (else `text` may end after the line `samples N`).
/// \throws TableError naming the file and line of what is wrong.
inline Table parse_table(const std::string& text_of_file, const std::string& path, bool values) {
  std::istringstream in(text_of_file);
  Table t;
  t.path = path;
  std::string text;
  int line = 0;
  auto fail = [&](const std::string& what) {
    throw TableError(path + ":" + std::to_string(line) + ": " + what);
  };
  auto number = [&](const std::string& s) { return detail::table_number(path, line, s); };
  auto integer = [&](const std::string& s) { return detail::table_integer(path, line, s); };
  if (!std::getline(in, text) || text != "gencoord-sweep-table 1")
    throw TableError(path + ": not a gencoord sweep table (written by gencoord sweep)");
  line = 1;
  while (std::getline(in, text)) {
    ++line;
    const auto space = text.find(' ');
    const std::string key = text.substr(0, space);
    const std::string value = space == std::string::npos ? "" : text.substr(space + 1);
    std::istringstream words(value);
    if (key == "digest") t.digest = value;
    else if (key == "build") t.build = value;
    else if (key == "model") t.model = value;
    else if (key == "integrator") t.integrator = value;
    else if (key == "method") t.method = value;
    else if (key == "dt") t.dt = number(value);
    else if (key == "t_end") t.t_end = number(value);
    else if (key == "steps") t.steps = integer(value);
    else if (key == "chunk") t.chunk = integer(value);
    else if (key == "seed") t.seed = integer(value);
    else if (key == "record_final_state") t.record_final_state = value == "1";
    else if (key == "record_energy_drift") t.record_energy_drift = value == "1";
    else if (key == "record_event_time") t.record_event_time = value == "1";
    else if (key == "trajectory_every") t.trajectory_every = integer(value);
    else if (key == "event_stop") t.event_stop = value == "1";
    else if (key == "event_text") t.event_text = value;
    else if (key == "sweep_file") t.sweep_file = value;
    else if (key == "sweep_line") t.sweep_lines.push_back(value);
    else if (key == "banner_line") t.banner_lines.push_back(value);
    else if (key == "grid_points") {
      for (std::string w; words >> w;) t.grid_points.push_back(integer(w));
    } else if (key == "event_clause") {
      EventClause c;
      std::string absolute, threshold;
      if (!(words >> c.kind >> c.coordinate >> absolute >> c.op >> threshold))
        fail("event_clause needs kind, coordinate, abs, op and value");
      c.absolute = absolute == "1";
      c.value = number(threshold);
      t.clauses.push_back(c);
      t.has_event = true;
    } else if (key == "parameter" || key == "initial") {
      std::string kind, name, amount;
      if (key == "initial" && !(words >> kind)) fail("initial needs q or v");
      if (!(words >> name >> amount)) fail(key + " needs a name and a value");
      if (key == "parameter") t.parameters.emplace_back(name, number(amount));
      else t.initial.push_back({kind, name, number(amount)});
    } else if (key == "column") {
      Column c;
      if (!(words >> c.kind >> c.name)) fail("column needs a kind and a name");
      t.columns.push_back(c);
    } else if (key == "samples") {
      t.samples = integer(value);
      break;
    } else {
      fail("unknown key '" + key + "'");
    }
  }
  if (t.digest.empty() || t.model.empty() || !(t.dt > 0) || t.steps < 0 || t.chunk < 1 ||
      t.samples < 1 || t.columns.empty() || t.trajectory_every < 0)
    throw TableError(path + ": incomplete sample table; run gencoord sweep again");
  if (!values) return t;
  const std::size_t width = t.columns.size();
  // a row holds `width` numbers and their separators: at least 2 width bytes, so a count the
  // rest of the file cannot hold is refused before anything is allocated for it
  const auto rest =
      static_cast<long long>(text_of_file.size()) - static_cast<long long>(in.tellg());
  if (in.tellg() < 0 || t.samples > rest / static_cast<long long>(2 * width) + 1)
    fail("the table ends before its " + std::to_string(t.samples) + " samples");
  t.values.resize(static_cast<std::size_t>(t.samples) * width);
  for (long long s = 0; s < t.samples; ++s) {
    ++line;
    if (!std::getline(in, text))
      fail("the table ends before its " + std::to_string(t.samples) + " samples");
    std::istringstream words(text);
    std::size_t k = 0;
    for (std::string w; words >> w; ++k) {
      if (k == width) fail("more values than the " + std::to_string(width) + " columns");
      t.values[static_cast<std::size_t>(s) * width + k] = number(w);
    }
    if (k != width) fail("fewer values than the " + std::to_string(width) + " columns");
  }
  return t;
}

/// The text of the file at `path`. \throws TableError if it cannot be read.
inline std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  if (!(in && text << in.rdbuf())) throw TableError(path + ": cannot read the sample table");
  return text.str();
}

/// The table's header: its text up to and including the line `samples N`.
inline std::string header_of(const std::string& text) {
  const auto at = text.find("\nsamples ");
  const auto end = at == std::string::npos ? at : text.find('\n', at + 1);
  return end == std::string::npos ? text : text.substr(0, end + 1);
}

}  // namespace gencoord::sweep
