// SPDX-License-Identifier: BSD-3-Clause
// Trajectory output as CSV: one row per state, with energy and particle positions.
#pragma once

#include <charconv>
#include <memory>
#include <ostream>
#include <stdexcept>
#include <string>
#include <utility>

#include "gencoord/io/output_file.hpp"
#include "gencoord/model/dissipated_work.hpp"
#include "gencoord/model/joint_limits.hpp"
#include "gencoord/model/model_traits.hpp"
#include "gencoord/model/state.hpp"

namespace gencoord {

/// Writes states of model M as CSV rows. Header:
///   t,q_<coord>...,v_<coord>...,energy[,work],<particle>_x,<particle>_y[,<particle>_z]...
///   [,fixed:<point>_x,fixed:<point>_y[,fixed:<point>_z]...]
/// where a model with generalized speeds (has_generalized_speeds_v) names its v columns
/// v_<speed> after M::speed_names instead, and a dissipative model (is_dissipative_v) has the
/// work W(t) of its dampers and friction since the first row (dissipated_work.hpp), so that
/// E(t) - E(0) - W(t) is the integrator's error: the rows must be a simulation's states in
/// order (1 + nq + nv + 1 + nx columns, one more for work, then dim per fixed point when M has
/// fixed points, see has_fixed_points_v; written on every row, since a prescribed pivot moves
/// with t). The
/// "fixed:" prefix, which no model name can contain, tells anchors from particles.
/// Numbers are written in the shortest form that reads back to the same double
/// (std::to_chars), independent of the stream's locale and precision.
/// A writer given a `companion` prefix (e.g. "maximal:") also has the positions of a second
/// model of the same particles, <companion><particle>_x, ..., after the fixed points; its
/// rows come from write(s, companion_x). A model with joint limits ends each row with one
/// column per limit, limit:<name>: -1 where its coordinate is on (or below) its lower end, +1
/// on (or above) its upper end, 0 inside its range.
/// Usable directly as a simulate() observer.
/// Write failures throw OutputError (output_file.hpp) with the path (or "the output stream"):
/// each row checks the stream, which sees a failed write at the next flush of its buffer;
/// close() (or flush()) makes sure everything reached the file.
template <class M>
class TrajectoryCsvWriter {
 public:
  /// Writes the header to `out`, which must outlive the writer.
  /// \throws OutputError if the stream has failed.
  TrajectoryCsvWriter(std::ostream& out, const ParamsOf<M>& p, std::string companion = {})
      : out_(&out), p_(p), companion_(std::move(companion)), work_(p) {
    write_header();
  }

  /// Creates (truncates) the file at `path` and writes the header.
  /// \throws OutputError if the file cannot be opened or written.
  TrajectoryCsvWriter(const std::string& path, const ParamsOf<M>& p, std::string companion = {})
      : file_(std::make_unique<OutputFile>(path)),
        out_(&file_->stream()),
        p_(p),
        companion_(std::move(companion)),
        work_(p) {
    write_header();
  }

  /// Appends one row for state s. \throws OutputError if the stream has failed;
  /// std::logic_error for a writer with a companion (write(s, companion_x) writes its rows).
  void operator()(const State<M>& s) {
    if (!companion_.empty())
      throw std::logic_error("gencoord: a trajectory with companion positions needs them");
    write_row(s);
    write_limits(s);
    end_row();
  }

  /// Appends one row for state s and the companion model's positions x (nx).
  /// \throws OutputError if the stream has failed.
  void write(const State<M>& s, const XVec<M>& companion_x) {
    write_row(s);
    for (int i = 0; i < M::nx; ++i) write_field(companion_x[i]);
    write_limits(s);
    end_row();
  }

  /// Rows the stream accepted (not counting the header); in the file once flush() or
  /// close() returns. After a write failure, the rows known to be written: those up to the
  /// last successful flush().
  long rows() const { return rows_; }

  /// The work column's value at the last row: W, the work of the dampers and friction since
  /// the first row (DissipatedWork); 0 for a model that is not dissipative.
  double work() const { return work_.work(); }

  /// Flushes the stream. \throws OutputError if this or an earlier write failed.
  void flush() {
    out_->flush();
    check();
    flushed_rows_ = rows_;
  }

  /// For a file opened by the writer: closes it and removes it (a regular file only), after
  /// a write failed. Does nothing for a stream given to the writer. True if it removed one.
  bool discard() noexcept { return file_ && file_->discard(); }

  /// Flushes and, for a file opened by the writer, closes it; no rows may follow.
  /// \throws OutputError if this or an earlier write failed.
  void close() {
    if (file_) {
      try {
        file_->close();
      } catch (const OutputError&) {
        rows_ = flushed_rows_;
        throw;
      }
      flushed_rows_ = rows_;
    } else {
      flush();
    }
  }

 private:
  static_assert(assert_model_v<M>);

  // t, q, v, energy, positions and fixed points, without the line's end
  void write_row(const State<M>& s) {
    write_number(s.t);
    for (int i = 0; i < M::nq; ++i) write_field(s.q[i]);
    for (int i = 0; i < nv_of_v<M>; ++i) write_field(s.v[i]);
    write_field(static_cast<double>(M::energy(s.q, s.v, s.t, p_)));
    if constexpr (is_dissipative_v<M>) write_field(work_(s));
    const XVec<M> x = M::positions(s.q, s.t, p_);
    for (int i = 0; i < M::nx; ++i) write_field(x[i]);
    if constexpr (has_fixed_points_v<M>) {
      const auto anchors = M::fixed_point_positions(s.t, p_);
      for (int i = 0; i < M::dim * M::num_fixed_points; ++i) write_field(anchors[i]);
    }
  }

  // each joint limit's side (limit_side: -1 lower end, +1 upper end, 0 inside)
  void write_limits(const State<M>& s) {
    if constexpr (has_joint_limits_v<M>) {
      for (int i = 0; i < M::num_limits; ++i) *out_ << ',' << limit_side<M>(s.q, i);
    } else {
      (void)s;
    }
  }
  void end_row() {
    *out_ << '\n';
    check();
    ++rows_;
  }

  void write_header() {
    static constexpr const char* kAxes[] = {"_x", "_y", "_z"};
    *out_ << 't';
    for (const char* c : M::coordinate_names) *out_ << ",q_" << c;
    if constexpr (has_generalized_speeds_v<M>) {
      for (const char* c : M::speed_names) *out_ << ",v_" << c;
    } else {
      for (const char* c : M::coordinate_names) *out_ << ",v_" << c;
    }
    *out_ << ",energy";
    if constexpr (is_dissipative_v<M>) *out_ << ",work";
    for (const char* particle : M::particle_names)
      for (int k = 0; k < M::dim; ++k) *out_ << ',' << particle << kAxes[k];
    if constexpr (has_fixed_points_v<M>) {
      for (const char* point : M::fixed_point_names)
        for (int k = 0; k < M::dim; ++k) *out_ << ",fixed:" << point << kAxes[k];
    }
    if (!companion_.empty()) {
      for (const char* particle : M::particle_names)
        for (int k = 0; k < M::dim; ++k) *out_ << ',' << companion_ << particle << kAxes[k];
    }
    if constexpr (has_joint_limits_v<M>) {
      for (const char* limit : M::limit_names) *out_ << ",limit:" << limit;
    }
    *out_ << '\n';
    check();
  }

  // throws OutputError, and rows() falls back to the rows known to be written
  void check() {
    if (*out_) return;
    rows_ = flushed_rows_;
    if (file_) file_->check();
    throw OutputError("the output stream", "writing");
  }

  void write_number(double x) {
    char buf[32];
    const auto result = std::to_chars(buf, buf + sizeof buf, x);
    out_->write(buf, result.ptr - buf);
  }

  void write_field(double x) {
    out_->put(',');
    write_number(x);
  }

  std::unique_ptr<OutputFile> file_;  // owned file, if constructed from a path
  std::ostream* out_;
  ParamsOf<M> p_;
  std::string companion_;   // prefix of the companion model's position columns, or empty
  DissipatedWork<M> work_;  // the work column's running sum (dissipative models only)
  long rows_ = 0;
  long flushed_rows_ = 0;
};

}  // namespace gencoord
