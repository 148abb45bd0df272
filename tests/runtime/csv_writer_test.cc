// SPDX-License-Identifier: BSD-3-Clause
#include "gencoord/io/csv_writer.hpp"
#include "gencoord/model/reduced_system.hpp"

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "gencoord/integrate/simulate.hpp"
#include "gencoord/io/output_file.hpp"
#include "hand_models.hpp"

namespace gencoord {
namespace {

using test_models::HandCoupled;
using test_models::HandPendulum;

// HandPendulum with two fixed points: a still pivot and a marker that moves with t, so the
// writer has to evaluate them on every row.
struct HandPendulumWithAnchors : HandPendulum {
  static constexpr int num_fixed_points = 2;
  static constexpr std::array<const char*, num_fixed_points> fixed_point_names{{"pivot", "mark"}};
  template <typename S>
  static Eigen::Matrix<S, dim * num_fixed_points, 1> fixed_point_positions(const S& t,
                                                                           const Params& p) {
    Eigen::Matrix<S, dim * num_fixed_points, 1> x;
    x << S(0), S(0), S(p.l) * t, S(-2);
    return x;
  }
};
static_assert(has_fixed_points_v<HandPendulumWithAnchors>);
static_assert(!has_fixed_points_v<HandPendulum>);

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::vector<double> fields_of(const std::string& line) {
  std::vector<double> fields;
  std::istringstream in(line);
  for (std::string f; std::getline(in, f, ',');) fields.push_back(std::strtod(f.c_str(), nullptr));
  return fields;
}

TEST(TrajectoryCsvWriter, PendulumHeaderAndOneRowPerObservedState) {
  const HandPendulum::Params p;
  std::ostringstream out;
  TrajectoryCsvWriter<HandPendulum> writer(out, p);
  State<HandPendulum> s;
  s.q[0] = 0.3;
  const State<HandPendulum> end =
      simulate(ReducedSystem<HandPendulum>(p), s, {Integrator::RK4, 0.05, 1.0}, writer);

  const std::vector<std::string> lines = lines_of(out.str());
  ASSERT_EQ(lines.size(), 1u + 21u);  // header + initial state + 20 steps
  EXPECT_EQ(lines[0], "t,q_theta,v_theta,energy,bob_x,bob_y");
  EXPECT_EQ(writer.rows(), 21);
  EXPECT_EQ(out.str().back(), '\n');

  // the last row reads back to exactly the final state
  const std::vector<double> last = fields_of(lines.back());
  ASSERT_EQ(last.size(), 6u);
  EXPECT_EQ(last[0], end.t);
  EXPECT_EQ(last[1], end.q[0]);
  EXPECT_EQ(last[2], end.v[0]);
  EXPECT_EQ(last[3], HandPendulum::energy(end.q, end.v, end.t, p));
  const XVec<HandPendulum> x = HandPendulum::positions(end.q, end.t, p);
  EXPECT_EQ(last[4], x[0]);
  EXPECT_EQ(last[5], x[1]);
}

TEST(TrajectoryCsvWriter, ThreeDimensionalHeaderAndFullPrecision) {
  const HandCoupled::Params p;
  std::ostringstream out;
  out.precision(3);  // the writer must not depend on the stream's precision
  TrajectoryCsvWriter<HandCoupled> writer(out, p);
  State<HandCoupled> s;
  s.t = 0.1;
  s.q << 1.0 / 3.0, -2.0e-300;
  s.v << 123456789.123456789, 0.0;
  writer(s);
  const std::vector<std::string> lines = lines_of(out.str());
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0], "t,q_u,q_w,v_u,v_w,energy,body_x,body_y,body_z");
  const std::vector<double> row = fields_of(lines[1]);
  ASSERT_EQ(row.size(), 9u);
  EXPECT_EQ(row[0], 0.1);
  EXPECT_EQ(row[1], 1.0 / 3.0);
  EXPECT_EQ(row[2], -2.0e-300);
  EXPECT_EQ(row[3], 123456789.123456789);
  EXPECT_EQ(row[8], 0.0);
}

TEST(TrajectoryCsvWriter, FixedPointColumnsFollowTheParticlesOnEveryRow) {
  HandPendulumWithAnchors::Params p;
  p.l = 0.5;
  std::ostringstream out;
  TrajectoryCsvWriter<HandPendulumWithAnchors> writer(out, p);
  State<HandPendulumWithAnchors> s;
  s.q[0] = 0.3;
  writer(s);
  s.t = 3.0;
  writer(s);
  const std::vector<std::string> lines = lines_of(out.str());
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0],
            "t,q_theta,v_theta,energy,bob_x,bob_y,fixed:pivot_x,fixed:pivot_y,fixed:mark_x,"
            "fixed:mark_y");
  const std::vector<double> first = fields_of(lines[1]);
  const std::vector<double> second = fields_of(lines[2]);
  ASSERT_EQ(first.size(), 10u);
  ASSERT_EQ(second.size(), 10u);
  EXPECT_EQ(first[4], HandPendulum::positions(s.q, 0.0, p)[0]);
  EXPECT_EQ(first[6], 0.0);
  EXPECT_EQ(first[7], 0.0);
  EXPECT_EQ(first[8], 0.0);   // mark_x = l t at t = 0
  EXPECT_EQ(second[8], 1.5);  // and at t = 3
  EXPECT_EQ(second[9], -2.0);
}

TEST(TrajectoryCsvWriter, CompanionPositionsFollowTheFixedPoints) {
  HandPendulumWithAnchors::Params p;
  std::ostringstream out;
  TrajectoryCsvWriter<HandPendulumWithAnchors> writer(out, p, "maximal:");
  State<HandPendulumWithAnchors> s;
  s.q[0] = 0.3;
  XVec<HandPendulumWithAnchors> companion;
  companion << 0.25, -0.75;
  writer.write(s, companion);
  EXPECT_THROW(writer(s), std::logic_error);  // a row without the companion's positions
  const std::vector<std::string> lines = lines_of(out.str());
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0],
            "t,q_theta,v_theta,energy,bob_x,bob_y,fixed:pivot_x,fixed:pivot_y,fixed:mark_x,"
            "fixed:mark_y,maximal:bob_x,maximal:bob_y");
  const std::vector<double> fields = fields_of(lines[1]);
  ASSERT_EQ(fields.size(), 12u);
  EXPECT_EQ(fields[10], 0.25);
  EXPECT_EQ(fields[11], -0.75);
  EXPECT_EQ(writer.rows(), 1);
}

TEST(TrajectoryCsvWriter, WritesToAFile) {
  const std::string path = ::testing::TempDir() + "gencoord_csv_writer_test.csv";
  {
    TrajectoryCsvWriter<HandPendulum> writer(path, HandPendulum::Params{});
    writer(State<HandPendulum>{});
    writer(State<HandPendulum>{});
  }
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(lines_of(text.str()).size(), 3u);
  std::remove(path.c_str());
  EXPECT_THROW(TrajectoryCsvWriter<HandPendulum>("/nonexistent_dir/x.csv", HandPendulum::Params{}),
               OutputError);
}

// /dev/full accepts open() and fails every write with ENOSPC: a full disk.
bool have_dev_full() { return std::ifstream("/dev/full").good(); }

TEST(TrajectoryCsvWriter, AFullDiskIsAnErrorWithThePathAndNoRowsAreClaimed) {
  if (!have_dev_full()) GTEST_SKIP() << "no /dev/full";
  State<HandPendulum> s;
  s.q[0] = 1.0;
  // a long run: the stream's buffer fills and its flush fails during the run
  try {
    TrajectoryCsvWriter<HandPendulum> writer("/dev/full", HandPendulum::Params{});
    try {
      simulate(ReducedSystem<HandPendulum>(HandPendulum::Params{}), s,
               {Integrator::RK4, 1e-3, 10.0}, writer);
      ADD_FAILURE() << "the run wrote 10001 rows to a full disk without an error";
    } catch (const OutputError& e) {
      EXPECT_EQ(e.path(), "/dev/full");
      EXPECT_THAT(e.what(), ::testing::HasSubstr("'/dev/full'"));
      EXPECT_THAT(e.what(), ::testing::HasSubstr("failed: No space left on device"));
      EXPECT_EQ(e.error_number(), ENOSPC);
      EXPECT_EQ(writer.rows(), 0);     // none reached the file
      EXPECT_FALSE(writer.discard());  // leaves the device alone: it is not a regular file
      EXPECT_TRUE(have_dev_full());
    }
  } catch (const OutputError& e) {
    ADD_FAILURE() << "the header alone should not fail: " << e.what();
  }
  // a short run fits in the buffer: close() reports it
  TrajectoryCsvWriter<HandPendulum> writer("/dev/full", HandPendulum::Params{});
  writer(s);
  writer(s);
  EXPECT_EQ(writer.rows(), 2);  // accepted by the stream, not yet in the file
  EXPECT_THROW(writer.close(), OutputError);
  EXPECT_EQ(writer.rows(), 0);
  TrajectoryCsvWriter<HandPendulum> flushed("/dev/full", HandPendulum::Params{});
  EXPECT_THROW(flushed.flush(), OutputError);
}

TEST(TrajectoryCsvWriter, DiscardRemovesTheWritersFile) {
  const std::string path = ::testing::TempDir() + "gencoord_csv_discard_test.csv";
  TrajectoryCsvWriter<HandPendulum> writer(path, HandPendulum::Params{});
  writer(State<HandPendulum>{});
  EXPECT_TRUE(writer.discard());
  EXPECT_FALSE(std::ifstream(path).good());
}

TEST(TrajectoryCsvWriter, AFailedStreamIsAnError) {
  std::ostringstream out;
  TrajectoryCsvWriter<HandPendulum> writer(out, HandPendulum::Params{});
  writer(State<HandPendulum>{});
  out.setstate(std::ios::badbit);
  EXPECT_THROW(writer(State<HandPendulum>{}), OutputError);
  EXPECT_EQ(writer.rows(), 0);  // no flush succeeded
}

TEST(TrajectoryCsvWriter, CloseAfterAGoodRunKeepsTheCount) {
  const std::string path = ::testing::TempDir() + "gencoord_csv_writer_close_test.csv";
  TrajectoryCsvWriter<HandPendulum> writer(path, HandPendulum::Params{});
  for (int k = 0; k < 5; ++k) writer(State<HandPendulum>{});
  writer.close();
  EXPECT_EQ(writer.rows(), 5);
  std::remove(path.c_str());
}

TEST(OutputFile, ReportsAFullDiskAtCloseAndAMissingFolderAtOpen) {
  if (!have_dev_full()) GTEST_SKIP() << "no /dev/full";
  OutputFile file("/dev/full");
  file.stream() << "some text\n";
  EXPECT_NO_THROW(file.check());  // still in the buffer
  try {
    file.close();
    ADD_FAILURE() << "close() on a full disk did not throw";
  } catch (const OutputError& e) {
    EXPECT_EQ(e.path(), "/dev/full");
  }
  EXPECT_THROW(OutputFile("/nonexistent_dir/x.txt"), OutputError);
}

}  // namespace
}  // namespace gencoord
