// SPDX-License-Identifier: BSD-3-Clause
// What a sweep records per sample, a chunk of samples at a time: the status and error, the
// final state, the energy drift, the event time and a decimated trajectory. A chunk's results
// travel from a worker rank to rank 0 packed into bytes, in a layout both know from the table.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace gencoord::sweep {

/// How a sample ended; stored as an HDF5 enum named by kStatusNames.
enum class Status : std::int8_t {
  kPending = 0,  // its chunk has not been run (the dataset's fill value)
  kOk = 1,
  kNotPositiveDefinite = 2,  // DynamicsError: Mt is not positive definite (singular)
  kMassMatrixNotFinite = 3,
  kForcesNotFinite = 4,
  kAccelerationNotFinite = 5,
  kNewtonFailed = 6,  // NewtonError in an implicit step
  kDiverged = 7,      // DivergedError: a step ended at NaN or inf
  kOtherError = 8,
  kDependentConstraints = 9,   // DynamicsError: the kinematic constraints are dependent here
  kConstraintsNotFinite = 10,  // DynamicsError: NaN or inf in the constraint Jacobian or bias
};

inline constexpr std::array<const char*, 11> kStatusNames{"pending",
                                                          "ok",
                                                          "mass_matrix_not_positive_definite",
                                                          "mass_matrix_not_finite",
                                                          "forces_not_finite",
                                                          "acceleration_not_finite",
                                                          "newton_not_converged",
                                                          "diverged",
                                                          "error",
                                                          "constraints_dependent",
                                                          "constraints_not_finite"};

/// Bytes of a sample's error text, zero padded.
inline constexpr std::size_t kErrorLength = 64;

/// The sizes every chunk's results share.
struct Layout {
  int nq = 0, nv = 0;  // coordinates and velocities (the generalized speeds where nv < nq)
  long long trajectory_points = 0;  // 0: no trajectory
  bool final_state = false, energy_drift = false, event_time = false;
};

/// The results of samples [begin, begin + count) of chunk `chunk`, one array per field, sample
/// by sample (q nq and v nv per sample; trajectories points x nq and points x nv per sample).
struct ChunkResults {
  long long chunk = -1, begin = 0, count = 0;
  std::vector<std::int8_t> status;
  std::vector<double> error_time;
  std::vector<char> error;  // count x kErrorLength
  std::vector<double> final_t, final_q, final_v, energy_drift, event_time;
  std::vector<double> trajectory_q, trajectory_v;

  /// Sized for `count` samples, every value NaN and every status pending.
  void reset(const Layout& layout, long long chunk_index, long long first, long long size) {
    chunk = chunk_index;
    begin = first;
    count = size;
    const auto n = static_cast<std::size_t>(size);
    const auto nq = static_cast<std::size_t>(layout.nq);
    const auto nv = static_cast<std::size_t>(layout.nv);
    const auto points = static_cast<std::size_t>(layout.trajectory_points);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    status.assign(n, static_cast<std::int8_t>(Status::kPending));
    error_time.assign(n, nan);
    error.assign(n * kErrorLength, '\0');
    final_t.assign(layout.final_state ? n : 0, nan);
    final_q.assign(layout.final_state ? n * nq : 0, nan);
    final_v.assign(layout.final_state ? n * nv : 0, nan);
    energy_drift.assign(layout.energy_drift ? n : 0, nan);
    event_time.assign(layout.event_time ? n : 0, nan);
    trajectory_q.assign(n * points * nq, nan);
    trajectory_v.assign(n * points * nv, nan);
  }

  /// The double-valued fields with their datasets' names, in the order pack() sends them; a
  /// field the layout does not record is empty.
  template <class Self>
  static auto double_fields(Self& r) {
    using Values =
        std::conditional_t<std::is_const_v<Self>, const std::vector<double>, std::vector<double>>;
    return std::array<std::pair<const char*, Values*>, 8>{{{"error_time", &r.error_time},
                                                           {"final_t", &r.final_t},
                                                           {"final_q", &r.final_q},
                                                           {"final_v", &r.final_v},
                                                           {"energy_drift", &r.energy_drift},
                                                           {"event_time", &r.event_time},
                                                           {"trajectory_q", &r.trajectory_q},
                                                           {"trajectory_v", &r.trajectory_v}}};
  }

  /// Sets sample i's error text (cut to kErrorLength - 1 bytes).
  void set_error(long long i, const std::string& text) {
    char* slot = error.data() + static_cast<std::size_t>(i) * kErrorLength;
    std::memset(slot, 0, kErrorLength);
    std::memcpy(slot, text.data(), std::min(text.size(), kErrorLength - 1));
  }
};

namespace detail {

template <class T>
void append_bytes(std::vector<char>* out, const std::vector<T>& values) {
  if (values.empty()) return;  // data() may be null
  const auto* bytes = reinterpret_cast<const char*>(values.data());
  out->insert(out->end(), bytes, bytes + values.size() * sizeof(T));
}

template <class T>
void take_bytes(const std::vector<char>& in, std::size_t* offset, std::vector<T>* values) {
  const std::size_t size = values->size() * sizeof(T);
  if (*offset + size > in.size()) throw std::runtime_error("sweep: a chunk's results are short");
  if (size > 0) std::memcpy(values->data(), in.data() + *offset, size);  // data() may be null
  *offset += size;
}

}  // namespace detail

/// The results as bytes: the chunk's index, first sample and size, then every array.
inline std::vector<char> pack(const ChunkResults& r) {
  std::vector<char> out;
  detail::append_bytes(&out, std::vector<long long>{r.chunk, r.begin, r.count});
  detail::append_bytes(&out, r.status);
  for (const auto& [name, values] : ChunkResults::double_fields(r))
    detail::append_bytes(&out, *values);
  detail::append_bytes(&out, r.error);
  return out;
}

/// The results pack() wrote, for samples of `layout`, at most `max_count` of them.
/// \throws std::runtime_error if the bytes do not have the layout's size.
inline ChunkResults unpack(const std::vector<char>& bytes, const Layout& layout,
                           long long max_count) {
  std::vector<long long> head(3);
  std::size_t offset = 0;
  detail::take_bytes(bytes, &offset, &head);
  if (head[2] < 0 || head[2] > max_count)
    throw std::runtime_error("sweep: a chunk's results hold " + std::to_string(head[2]) +
                             " samples");
  ChunkResults r;
  r.reset(layout, head[0], head[1], head[2]);
  detail::take_bytes(bytes, &offset, &r.status);
  for (const auto& [name, values] : ChunkResults::double_fields(r))
    detail::take_bytes(bytes, &offset, values);
  detail::take_bytes(bytes, &offset, &r.error);
  if (offset != bytes.size()) throw std::runtime_error("sweep: a chunk's results are too long");
  return r;
}

}  // namespace gencoord::sweep
