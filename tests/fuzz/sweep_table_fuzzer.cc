// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: the sweep program's sample-table reader (drivers/sweep/table.hpp) on
// arbitrary bytes. The first byte says whether the samples' values are read too (rank 0) or
// only the settings (the other ranks); the rest is the file. Each input must give a table
// whose values fill its samples x columns, or a TableError; another exception (bad_alloc for a
// count the file cannot hold), a crash or a sanitizer report is a finding. Built and run by
// scripts/fuzz.sh.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "sweep/table.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
  const bool values = data[0] & 1;
  try {
    const gencoord::sweep::Table table = gencoord::sweep::parse_table(text, "fuzz.table", values);
    const auto expected =
        values ? static_cast<std::size_t>(table.samples) * table.columns.size() : 0;
    if (table.values.size() != expected || table.chunks() < 1) std::abort();
  } catch (const gencoord::sweep::TableError&) {
    // the documented refusal of a file that is no sample table
  }
  return 0;
}
