// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What the mesh readers share (private): numbered lines split into words, numbers parsed with
// errors that name the file and line, and the checks and clean-up of the mesh read.

#include <Eigen/Core>
#include <array>
#include <istream>
#include <string>
#include <vector>

#include "gencoord/deformable/errors.hpp"
#include "gencoord/deformable/mesh.hpp"

namespace gencoord::deformable::detail {

/// The lines of a text file, one at a time, split into words, with their numbers for messages.
class TextLines {
 public:
  /// `comment`: a character that starts a comment up to the end of the line ('\0': none).
  TextLines(std::istream& in, std::string name, char comment = '\0');

  /// Reads the next line that has a word; false at the end of the file.
  bool next();
  /// Reads the next line that has a word; at the end of the file throws "the file ends
  /// <where>; it is truncated".
  void expect_next(const std::string& where);

  const std::vector<std::string>& words() const { return words_; }
  int line() const { return line_; }
  const std::string& name() const { return name_; }

  /// Throws MeshFileError "name:line: what" at the current line.
  [[noreturn]] void fail(const std::string& what, int element = -1, int node = -1) const;
  /// The same at another line.
  [[noreturn]] void fail_at(int line, const std::string& what, int element = -1,
                            int node = -1) const;

  /// Throws unless the line has `count` words: "<what>: expected <count> numbers (<names>),
  /// got <n>".
  void expect_words(size_t count, const std::string& what, const std::string& names) const;
  /// Word k as an integer / a finite number, or throws naming `what`.
  long long integer(size_t k, const std::string& what) const;
  /// Word k as a count: an integer, or throws naming `what`, also when it is negative.
  long long count(size_t k, const std::string& what) const;
  double real(size_t k, const std::string& what) const;

 private:
  std::istream& in_;
  std::string name_;
  char comment_;
  int line_ = 0;
  std::string text_;
  std::vector<std::string> words_;
};

/// A mesh as read, before its checks: nodes with their label in the file (tag or number), and
/// elements (indices into `nodes`) with their line and label.
template <int Dim>
struct RawMesh {
  std::vector<Eigen::Matrix<double, Dim, 1>> nodes;
  std::vector<long long> node_labels;
  std::vector<std::array<int, Dim + 1>> elements;
  std::vector<int> element_lines;
  std::vector<long long> element_labels;
};

/// Checks the elements of `raw` (no repeated node, area or volume above kMinRelativeMeasure
/// times the longest edge to the power Dim), orients them positively, drops the nodes that no
/// element uses and renumbers the rest in file order. Refusals name `name` and the line.
template <int Dim>
SimplexMesh<Dim> finish_mesh(RawMesh<Dim> raw, const std::string& name);

}  // namespace gencoord::deformable::detail
