// SPDX-License-Identifier: BSD-3-Clause
// What the sweep program's ranks exchange, without MPI: a chunk's results packed to bytes and
// back, and the sample table rank 0 reads. Built under the sanitizers with the runtime suites.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "sweep/results.hpp"
#include "sweep/table.hpp"

namespace gencoord::sweep {
namespace {

ChunkResults filled(const Layout& layout, long long count) {
  ChunkResults r;
  r.reset(layout, 3, 30, count);
  double x = 0.5;
  for (auto* field : {&r.error_time, &r.final_t, &r.final_q, &r.final_v, &r.energy_drift,
                      &r.event_time, &r.trajectory_q, &r.trajectory_v})
    for (double& value : *field) value = (x += 0.25);
  for (long long i = 0; i < count; ++i) r.status[static_cast<std::size_t>(i)] = 1;
  r.set_error(count - 1, "at q = (0.5, 0)");
  return r;
}

void expect_equal(const ChunkResults& a, const ChunkResults& b) {
  EXPECT_EQ(a.chunk, b.chunk);
  EXPECT_EQ(a.begin, b.begin);
  EXPECT_EQ(a.count, b.count);
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.error, b.error);
  EXPECT_EQ(a.error_time, b.error_time);
  EXPECT_EQ(a.final_q, b.final_q);
  EXPECT_EQ(a.energy_drift, b.energy_drift);
  EXPECT_EQ(a.event_time, b.event_time);
  EXPECT_EQ(a.trajectory_q, b.trajectory_q);
  EXPECT_EQ(a.trajectory_v, b.trajectory_v);
}

TEST(SweepResults, PackedBytesUnpackToTheSameResultsWithAndWithoutOptionalFields) {
  const Layout bare{2, 2, 0, false, false, false};  // optional fields empty: null data()
  const Layout full{2, 2, 5, true, true, true};
  const Layout speeds{7, 6, 5, true, true, true};  // a free body: nv < nq
  for (const Layout& layout : {bare, full, speeds}) {
    const ChunkResults r = filled(layout, 4);
    expect_equal(unpack(pack(r), layout, 4), r);
  }
}

TEST(SweepResults, ErrorTextIsCutAndZeroPadded) {
  ChunkResults r;
  r.reset(Layout{1, 1, 0, false, false, false}, 0, 0, 2);
  r.set_error(1, std::string(200, 'x'));
  const char* slot = r.error.data() + kErrorLength;
  EXPECT_EQ(std::string(slot), std::string(kErrorLength - 1, 'x'));
  EXPECT_EQ(r.error[0], '\0');
}

TEST(SweepResults, BytesOfAnotherSizeAreRefused) {
  const Layout layout{2, 2, 0, true, true, false};
  std::vector<char> bytes = pack(filled(layout, 3));
  EXPECT_THROW(unpack(bytes, layout, 2), std::runtime_error);  // more samples than a chunk
  bytes.push_back('\0');
  EXPECT_THROW(unpack(bytes, layout, 3), std::runtime_error);
  bytes.resize(bytes.size() - 9);
  EXPECT_THROW(unpack(bytes, layout, 3), std::runtime_error);
}

const char* const kTable =
    "gencoord-sweep-table 1\n"
    "digest abc\n"
    "build entry\n"
    "model double_pendulum\n"
    "integrator rk4\n"
    "method grid\n"
    "dt 0.01\n"
    "t_end 1.0\n"
    "steps 100\n"
    "chunk 2\n"
    "record_final_state 1\n"
    "trajectory_every 0\n"
    "event_clause q theta1 1 > 3.141592653589793\n"
    "parameter g 9.81\n"
    "initial v theta2 0.5\n"
    "column q theta1\n"
    "column q theta2\n"
    "samples 3\n"
    "-0.5 0.1\n"
    "0.0 0.2\n"
    "0.5 0.30000000000000004\n";

TEST(SweepTable, IsReadWithItsSettingsAndRows) {
  const Table t = parse_table(kTable, "t.table", true);
  EXPECT_EQ(t.model, "double_pendulum");
  EXPECT_EQ(t.steps, 100);
  EXPECT_EQ(t.chunks(), 2);
  Table huge = t;  // chunks() cannot overflow at the largest counts
  huge.samples = huge.chunk = std::numeric_limits<long long>::max();
  EXPECT_EQ(huge.chunks(), 1);
  EXPECT_EQ(t.chunk_size(1), 1);
  ASSERT_EQ(t.clauses.size(), 1u);
  EXPECT_TRUE(t.clauses[0].absolute);
  EXPECT_EQ(t.clauses[0].value, 3.141592653589793);
  EXPECT_EQ(t.initial.at(0).name, "theta2");
  EXPECT_EQ(t.row(2)[1], 0.30000000000000004);  // read back as the same double
  EXPECT_EQ(header_of(kTable).substr(header_of(kTable).size() - 10), "samples 3\n");
}

TEST(SweepTable, ShortOrWideRowsAndUnknownKeysNameTheLine) {
  std::string short_rows = kTable;
  short_rows.resize(short_rows.size() - std::strlen("0.5 0.30000000000000004\n"));
  for (const auto& [text, phrase] : std::vector<std::pair<std::string, std::string>>{
           {short_rows, "t.table:21: the table ends before its 3 samples"},
           {std::string(kTable).replace(std::string(kTable).find("0.0 0.2"), 7, "0.0 0.2 9"),
            "t.table:20: more values than the 2 columns"},
           {std::string(kTable).replace(std::string(kTable).find("build"), 5, "built"),
            "t.table:3: unknown key 'built'"},
           // a count the file cannot hold is refused before its rows are allocated (found by
           // scripts/fuzz.sh: 10^17 samples of 2 columns asked for 1.6 EB)
           {std::string(kTable).replace(std::string(kTable).find("samples 3"), 9,
                                        "samples 100000000000000000"),
            "t.table:18: the table ends before its 100000000000000000 samples"}}) {
    try {
      parse_table(text, "t.table", true);
      ADD_FAILURE() << "accepted: " << phrase;
    } catch (const TableError& e) {
      EXPECT_EQ(std::string(e.what()).substr(0, phrase.size()), phrase);
    }
  }
}

}  // namespace
}  // namespace gencoord::sweep
