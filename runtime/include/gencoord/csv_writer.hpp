// Trajectory output as CSV: one row per state, with energy and particle positions.
#pragma once

#include <charconv>
#include <fstream>
#include <memory>
#include <ostream>
#include <stdexcept>
#include <string>

#include "gencoord/model_traits.hpp"
#include "gencoord/state.hpp"

namespace gencoord {

/// Writes states of model M as CSV rows. Header:
///   t,q_<coord>...,v_<coord>...,energy,<particle>_x,<particle>_y[,<particle>_z]...
///   [,fixed:<point>_x,fixed:<point>_y[,fixed:<point>_z]...]
/// (1 + 2 nq + 1 + nx columns, then dim per fixed point when M has fixed points, see
/// has_fixed_points_v; written on every row, since a prescribed pivot moves with t). The
/// "fixed:" prefix, which no model name can contain, tells anchors from particles.
/// Numbers are written in the shortest form that reads back to the same double
/// (std::to_chars), independent of the stream's locale and precision.
/// Usable directly as a simulate() observer.
template <class M>
class TrajectoryCsvWriter {
 public:
  /// Writes the header to `out`, which must outlive the writer.
  TrajectoryCsvWriter(std::ostream& out, const ParamsOf<M>& p) : out_(&out), p_(p) {
    write_header();
  }

  /// Creates (truncates) the file at `path` and writes the header.
  /// \throws std::runtime_error if the file cannot be opened.
  TrajectoryCsvWriter(const std::string& path, const ParamsOf<M>& p)
      : file_(std::make_unique<std::ofstream>(path)), out_(file_.get()), p_(p) {
    if (!*file_) throw std::runtime_error("gencoord: cannot open '" + path + "' for writing");
    write_header();
  }

  /// Appends one row for state s.
  void operator()(const State<M>& s) {
    write_number(s.t);
    for (int i = 0; i < M::nq; ++i) write_field(s.q[i]);
    for (int i = 0; i < M::nq; ++i) write_field(s.v[i]);
    write_field(static_cast<double>(M::energy(s.q, s.v, s.t, p_)));
    const XVec<M> x = M::positions(s.q, s.t, p_);
    for (int i = 0; i < M::nx; ++i) write_field(x[i]);
    if constexpr (has_fixed_points_v<M>) {
      const auto anchors = M::fixed_point_positions(s.t, p_);
      for (int i = 0; i < M::dim * M::num_fixed_points; ++i) write_field(anchors[i]);
    }
    *out_ << '\n';
    ++rows_;
  }

  /// Rows written so far (not counting the header).
  long rows() const { return rows_; }

 private:
  static_assert(assert_model_v<M>);

  void write_header() {
    static constexpr const char* kAxes[] = {"_x", "_y", "_z"};
    *out_ << 't';
    for (const char* c : M::coordinate_names) *out_ << ",q_" << c;
    for (const char* c : M::coordinate_names) *out_ << ",v_" << c;
    *out_ << ",energy";
    for (const char* particle : M::particle_names)
      for (int k = 0; k < M::dim; ++k) *out_ << ',' << particle << kAxes[k];
    if constexpr (has_fixed_points_v<M>) {
      for (const char* point : M::fixed_point_names)
        for (int k = 0; k < M::dim; ++k) *out_ << ",fixed:" << point << kAxes[k];
    }
    *out_ << '\n';
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

  std::unique_ptr<std::ofstream> file_;  // owned file, if constructed from a path
  std::ostream* out_;
  ParamsOf<M> p_;
  long rows_ = 0;
};

}  // namespace gencoord
