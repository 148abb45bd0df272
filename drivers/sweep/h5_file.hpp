// SPDX-License-Identifier: BSD-3-Clause
// The results file: one HDF5 file that rank 0 alone writes (serial HDF5; docs/sweep.md says
// why). Created whole under a temporary name and renamed, with every dataset allocated at
// its full, fixed size and contiguous, so that writing a chunk's results later changes raw
// data only, never the file's metadata: a run killed at any moment leaves a file that opens.
// A chunk counts as done once its data is written, flushed and synced to disk, and only then
// is its flag in `chunk_done` set (chunks that arrive together share the syncs).
#pragma once

#include <fcntl.h>
#include <hdf5.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "sweep/results.hpp"
#include "sweep/table.hpp"

namespace gencoord::sweep {

class ResultsError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// An HDF5 identifier, closed when it goes out of scope.
class H5Id {
 public:
  H5Id() = default;
  H5Id(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  H5Id(H5Id&& other) noexcept { *this = std::move(other); }
  H5Id& operator=(H5Id&& other) noexcept {
    std::swap(id_, other.id_);
    std::swap(close_, other.close_);
    return *this;
  }
  H5Id(const H5Id&) = delete;
  H5Id& operator=(const H5Id&) = delete;
  ~H5Id() {
    if (id_ >= 0 && close_) close_(id_);
  }
  hid_t get() const { return id_; }
  /// Closes it now; HDF5's status (negative: failed, as a close that cannot flush).
  herr_t close() {
    const herr_t status = id_ >= 0 && close_ ? close_(id_) : 0;
    id_ = -1;
    return status;
  }

 private:
  hid_t id_ = -1;
  herr_t (*close_)(hid_t) = nullptr;
};

namespace detail {

// the first message of HDF5's error stack, which says what failed, and the system's reason
// where a message of the stack quotes an errno (the file driver's "errno = 28": a full disk)
inline std::string h5_message() {
  struct Found {
    std::string message;
    int error_number = 0;
  } found;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_DOWNWARD,
      [](unsigned, const H5E_error2_t* e, void* out) -> herr_t {
        auto* f = static_cast<Found*>(out);
        if (!e->desc) return 0;
        if (f->message.empty()) f->message = e->desc;
        const char* quoted = std::strstr(e->desc, "errno = ");
        if (quoted && f->error_number == 0) f->error_number = std::atoi(quoted + 8);
        return 0;
      },
      &found);
  std::string message = found.message.empty() ? "no detail" : found.message;
  if (found.error_number > 0) message += std::string(": ") + std::strerror(found.error_number);
  return message;
}

class H5Calls {
 public:
  explicit H5Calls(std::string path) : path_(std::move(path)) {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // errors become exceptions, not printouts
  }
  // `id` unless it is negative (HDF5's failure), in which case a ResultsError naming `what`
  hid_t check(hid_t id, const std::string& what) const {
    if (id < 0) throw ResultsError(path_ + ": cannot " + what + " (HDF5: " + h5_message() + ")");
    return id;
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

inline H5Id string_type(std::size_t size) {
  H5Id type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), std::max<std::size_t>(size, 1));
  H5Tset_strpad(type.get(), H5T_STR_NULLPAD);
  return type;
}

inline H5Id status_type() {
  H5Id type(H5Tenum_create(H5T_NATIVE_INT8), H5Tclose);
  for (std::size_t k = 0; k < kStatusNames.size(); ++k) {
    const auto value = static_cast<std::int8_t>(k);
    H5Tenum_insert(type.get(), kStatusNames[k], &value);
  }
  return type;
}

}  // namespace detail

class ResultsFile {
 public:
  /// Creates the results file of `table` at `path` (replacing one there): every dataset at
  /// its full size, filled with NaN (or pending, or 0), the samples' values, and the sweep,
  /// the generator's banner and the settings as attributes (`coordinates` and `speeds` name
  /// q's and v's entries). \throws ResultsError.
  static void create(const std::string& path, const Table& table, const Layout& layout,
                     const std::vector<std::string>& coordinates,
                     const std::vector<std::string>& speeds) {
    const std::string partial = path + ".partial";
    try {
      write_new(partial, table, layout, coordinates, speeds);
    } catch (...) {
      std::remove(partial.c_str());  // a half-made file is no result (it may hold gigabytes)
      throw;
    }
    sync_path(partial);
    if (std::rename(partial.c_str(), path.c_str()) != 0) {
      std::remove(partial.c_str());
      throw ResultsError(partial + ": cannot rename it to " + path);
    }
    const std::size_t slash = path.rfind('/');
    sync_path(slash == std::string::npos ? "." : slash == 0 ? "/" : path.substr(0, slash));
  }

  enum class Access { kReadOnly, kReadWrite };

  /// Opens the results file at `path` of `table`, to write chunks into it or (kReadOnly)
  /// only to read it. \throws ResultsError if it cannot be opened or holds another sweep
  /// (another digest).
  ResultsFile(const std::string& path, const Table& table, const Layout& layout,
              Access access = Access::kReadWrite)
      : h5_(path), layout_(layout) {
    const unsigned flags = access == Access::kReadOnly ? H5F_ACC_RDONLY : H5F_ACC_RDWR;
    file_ = H5Id(h5_.check(H5Fopen(path.c_str(), flags, H5P_DEFAULT),
                           "open it as a sweep's results (is a sweep still writing it? if "
                           "not, remove it to start again)"),
                 H5Fclose);
    const std::string digest = read_string_attribute("digest");
    if (digest != table.digest)
      throw ResultsError(path +
                         ": holds the results of another sweep, or of this one run by "
                         "another build of the model's program; remove it (or use another "
                         "output folder) to start again");
    for (const char* name :
         {"status", "error_time", "error", "final_t", "final_q", "final_v", "energy_drift",
          "event_time", "trajectory_q", "trajectory_v", "chunk_done"}) {
      if (H5Lexists(file_.get(), name, H5P_DEFAULT) > 0)
        datasets_[name] = H5Id(h5_.check(H5Dopen2(file_.get(), name, H5P_DEFAULT),
                                         std::string("open dataset ") + name),
                               H5Dclose);
    }
    if (datasets_.count("chunk_done") == 0 ||
        chunk_done().size() != static_cast<std::size_t>(table.chunks()))
      throw ResultsError(path + ": its chunk_done does not match the table's " +
                         std::to_string(table.chunks()) + " chunks; remove it to start again");
  }

  /// Whether each chunk is done (1) or not (0).
  std::vector<std::uint8_t> chunk_done() const {
    return read_all<std::uint8_t>("chunk_done", H5T_NATIVE_UINT8);
  }
  std::vector<std::int8_t> statuses() const {
    const H5Id type = detail::status_type();
    return read_all<std::int8_t>("status", type.get());
  }
  std::vector<double> event_times() const {
    return datasets_.count("event_time") ? read_all<double>("event_time", H5T_NATIVE_DOUBLE)
                                         : std::vector<double>{};
  }

  /// Writes the results of some chunks, syncs them to disk, then marks the chunks done (and
  /// syncs again): two syncs however many chunks.
  void write(const std::vector<ChunkResults>& chunks) {
    for (const ChunkResults& r : chunks) write_data(r);
    sync();  // the data is on disk before the flags that say so
    const std::uint8_t done = 1;
    for (const ChunkResults& r : chunks)
      write_rows("chunk_done", H5T_NATIVE_UINT8, r.chunk, 1, &done);
    sync();
  }

 private:
  // the whole file, at `partial`: every dataset allocated, the samples, the attributes
  static void write_new(const std::string& partial, const Table& table, const Layout& layout,
                        const std::vector<std::string>& coordinates,
                        const std::vector<std::string>& speeds) {
    const detail::H5Calls h5(partial);
    H5Id file(h5.check(H5Fcreate(partial.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT),
                       "create the file"),
              H5Fclose);
    Creator make{h5, file.get(), table.samples};
    const hsize_t n = static_cast<hsize_t>(table.samples);
    const auto nq = static_cast<hsize_t>(layout.nq);
    const auto nv = static_cast<hsize_t>(layout.nv);
    const auto points = static_cast<hsize_t>(layout.trajectory_points);
    const H5Id samples = make.doubles("samples", {n, table.columns.size()});
    make.write_all(samples.get(), H5T_NATIVE_DOUBLE, table.values.data(), "samples");
    std::vector<std::string> labels;
    for (const Column& c : table.columns) labels.push_back(c.label());
    make.strings(samples.get(), "columns", labels);
    const H5Id status_type = detail::status_type();
    const auto pending = static_cast<std::int8_t>(Status::kPending);
    make.dataset("status", status_type.get(), {n}, &pending);
    make.doubles("error_time", {n});
    const H5Id error_type = detail::string_type(kErrorLength);
    const std::vector<char> no_error(kErrorLength, '\0');
    make.dataset("error", error_type.get(), {n}, no_error.data());
    if (layout.final_state) {
      make.doubles("final_t", {n});
      make.doubles("final_q", {n, nq});
      make.doubles("final_v", {n, nv});
    }
    if (layout.energy_drift) make.doubles("energy_drift", {n});
    if (layout.event_time) make.doubles("event_time", {n});
    if (points > 0) {
      const H5Id times = make.doubles("trajectory_t", {points});
      std::vector<double> t(points);
      for (hsize_t j = 0; j < points; ++j)
        t[j] = static_cast<double>(j * static_cast<hsize_t>(table.trajectory_every)) * table.dt;
      make.write_all(times.get(), H5T_NATIVE_DOUBLE, t.data(), "trajectory_t");
      make.doubles("trajectory_q", {n, points, nq});
      make.doubles("trajectory_v", {n, points, nv});
    }
    const std::uint8_t zero = 0;
    make.dataset("chunk_done", H5T_STD_U8LE, {static_cast<hsize_t>(table.chunks())}, &zero);
    make.attributes(table, coordinates, speeds);
    h5.check(H5Fflush(file.get(), H5F_SCOPE_GLOBAL), "flush the new file");
    h5.check(file.close(), "close the new file");
  }

  void write_data(const ChunkResults& r) {
    const H5Id status_type = detail::status_type();
    const H5Id error_type = detail::string_type(kErrorLength);
    auto rows = [&](const char* name, hid_t type, const void* data) {
      write_rows(name, type, r.begin, r.count, data);
    };
    rows("status", status_type.get(), r.status.data());
    rows("error", error_type.get(), r.error.data());
    for (const auto& [name, values] : ChunkResults::double_fields(r))
      if (!values->empty()) rows(name, H5T_NATIVE_DOUBLE, values->data());  // recorded
  }

  // makes the datasets and attributes of a new file
  struct Creator {
    const detail::H5Calls& h5;
    hid_t file;
    long long samples;

    H5Id dataset(const char* name, hid_t type, const std::vector<hsize_t>& dims,
                 const void* fill) const {
      H5Id space(h5.check(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr),
                          std::string("describe dataset ") + name),
                 H5Sclose);
      H5Id plist(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
      H5Pset_layout(plist.get(), H5D_CONTIGUOUS);
      H5Pset_alloc_time(plist.get(), H5D_ALLOC_TIME_EARLY);  // no allocation while running
      H5Pset_obj_track_times(plist.get(), 0);  // no clock times: the same run, the same bytes
      if (fill) {
        H5Pset_fill_value(plist.get(), type, fill);
        H5Pset_fill_time(plist.get(), H5D_FILL_TIME_ALLOC);
      }
      return H5Id(
          h5.check(H5Dcreate2(file, name, type, space.get(), H5P_DEFAULT, plist.get(), H5P_DEFAULT),
                   std::string("create dataset ") + name),
          H5Dclose);
    }
    H5Id doubles(const char* name, const std::vector<hsize_t>& dims) const {
      const double nan = std::numeric_limits<double>::quiet_NaN();
      return dataset(name, H5T_IEEE_F64LE, dims, &nan);
    }
    void write_all(hid_t dataset, hid_t type, const void* data, const char* name) const {
      h5.check(H5Dwrite(dataset, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data),
               std::string("write dataset ") + name);
    }
    void attribute(hid_t object, const char* name, hid_t type, const std::vector<hsize_t>& dims,
                   const void* data) const {
      H5Id space(dims.empty()
                     ? H5Screate(H5S_SCALAR)
                     : H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr),
                 H5Sclose);
      H5Id attribute(h5.check(H5Acreate2(object, name, type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                              std::string("create attribute ") + name),
                     H5Aclose);
      h5.check(H5Awrite(attribute.get(), type, data), std::string("write attribute ") + name);
    }
    void text(hid_t object, const char* name, const std::string& value) const {
      const H5Id type = detail::string_type(value.size());
      attribute(object, name, type.get(), {}, value.empty() ? "" : value.data());
    }
    void strings(hid_t object, const char* name, const std::vector<std::string>& values) const {
      std::size_t width = 1;
      for (const auto& v : values) width = std::max(width, v.size());
      std::vector<char> packed(values.size() * width, '\0');
      for (std::size_t k = 0; k < values.size(); ++k)
        std::copy(values[k].begin(), values[k].end(), packed.begin() + k * width);
      const H5Id type = detail::string_type(width);
      attribute(object, name, type.get(), {values.size()}, packed.data());
    }
    void number(hid_t object, const char* name, double value) const {
      attribute(object, name, H5T_NATIVE_DOUBLE, {}, &value);
    }
    void integers(hid_t object, const char* name, const std::vector<long long>& values) const {
      if (values.size() == 1) attribute(object, name, H5T_NATIVE_LLONG, {}, values.data());
      else attribute(object, name, H5T_NATIVE_LLONG, {values.size()}, values.data());
    }
    void attributes(const Table& t, const std::vector<std::string>& coordinates,
                    const std::vector<std::string>& speeds) const {
      auto joined = [](const std::vector<std::string>& lines) {
        std::string all;
        for (const auto& line : lines) all += line + "\n";
        return all;
      };
      text(file, "format", "gencoord-sweep 1");
      text(file, "sweep", joined(t.sweep_lines));
      text(file, "sweep_file", t.sweep_file);
      text(file, "banner", joined(t.banner_lines));
      text(file, "digest", t.digest);
      text(file, "build", t.build);
      text(file, "model", t.model);
      strings(file, "coordinates", coordinates);
      strings(file, "speeds", speeds);
      text(file, "integrator", t.integrator);
      number(file, "dt", t.dt);
      number(file, "t_end", t.t_end);
      integers(file, "steps", {t.steps});
      integers(file, "chunk", {t.chunk});
      integers(file, "samples", {t.samples});
      text(file, "method", t.method);
      if (t.seed >= 0) integers(file, "seed", {t.seed});
      if (!t.grid_points.empty()) integers(file, "grid_points", t.grid_points);
      if (t.has_event) {
        text(file, "event", t.event_text);
        integers(file, "event_stops_sample", {t.event_stop ? 1 : 0});
      }
    }
  };

  // rows [begin, begin + count) of a dataset (its first dimension)
  void write_rows(const char* name, hid_t type, long long begin, long long rows, const void* data) {
    if (rows == 0) return;
    const hid_t dataset = datasets_.at(name).get();
    H5Id space(h5_.check(H5Dget_space(dataset), std::string("read the shape of ") + name),
               H5Sclose);
    const int rank = H5Sget_simple_extent_ndims(space.get());
    std::vector<hsize_t> dims(static_cast<std::size_t>(std::max(rank, 1)));
    H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
    std::vector<hsize_t> start(dims.size(), 0), count = dims;
    start[0] = static_cast<hsize_t>(begin);
    count[0] = static_cast<hsize_t>(rows);
    h5_.check(H5Sselect_hyperslab(space.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(),
                                  nullptr),
              std::string("select rows of ") + name);
    H5Id memory(H5Screate_simple(rank, count.data(), nullptr), H5Sclose);
    h5_.check(H5Dwrite(dataset, type, memory.get(), space.get(), H5P_DEFAULT, data),
              std::string("write rows of ") + name);
  }

  template <class T>
  std::vector<T> read_all(const char* name, hid_t type) const {
    const hid_t dataset = datasets_.at(name).get();
    H5Id space(H5Dget_space(dataset), H5Sclose);
    std::vector<T> values(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space.get())));
    h5_.check(H5Dread(dataset, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
              std::string("read dataset ") + name);
    return values;
  }

  std::string read_string_attribute(const char* name) const {
    if (H5Aexists(file_.get(), name) <= 0)
      throw ResultsError(h5_.path() + ": not a gencoord sweep's results (no '" + name +
                         "' attribute); remove it to start again");
    H5Id attribute(
        h5_.check(H5Aopen(file_.get(), name, H5P_DEFAULT), std::string("open attribute ") + name),
        H5Aclose);
    H5Id type(H5Aget_type(attribute.get()), H5Tclose);
    std::string value(H5Tget_size(type.get()), '\0');
    h5_.check(H5Aread(attribute.get(), type.get(), value.data()),
              std::string("read attribute ") + name);
    return value.substr(0, value.find('\0'));
  }

  // HDF5's buffers to the file, and the file to the disk
  void sync() {
    h5_.check(H5Fflush(file_.get(), H5F_SCOPE_GLOBAL), "flush the file");
    void* handle = nullptr;
    h5_.check(H5Fget_vfd_handle(file_.get(), H5P_DEFAULT, &handle), "find its file handle");
    if (::fsync(*static_cast<int*>(handle)) != 0)
      throw ResultsError(h5_.path() + ": cannot sync it to disk");
  }

  static void sync_path(const std::string& path) {
    const int fd = ::open(path.c_str(), O_RDONLY);
    const bool synced = fd >= 0 && ::fsync(fd) == 0;
    if (fd >= 0) ::close(fd);
    if (!synced) throw ResultsError(path + ": cannot sync it to disk");
  }

  detail::H5Calls h5_;
  Layout layout_;
  H5Id file_;
  std::map<std::string, H5Id> datasets_;
};

}  // namespace gencoord::sweep
