// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// \file errors.hpp
/// Exceptions of the deformable library. Each message names what was refused (element, node,
/// spring or parameter), its value, and what would be accepted. Bad step sizes throw the
/// runtime's gencoord::StepSizeError.

#include <stdexcept>
#include <string>
#include <utility>

namespace gencoord::deformable {

/// A mesh that cannot become a mass-spring object: an element index out of range, a repeated
/// or unused node, a node that is not finite, an element of (nearly) zero area or volume.
class MeshError : public std::invalid_argument {
 public:
  MeshError(const std::string& what, int element, int node)
      : std::invalid_argument(what), element_(element), node_(node) {}
  int element() const { return element_; }  ///< the element at fault, -1 if none
  int node() const { return node_; }        ///< the node at fault, -1 if none

 private:
  int element_, node_;
};

/// A mesh file that cannot be read (mesh_io.hpp): the message starts with "file:line: " and
/// says what is wrong there and what to do; element() and node() are those of the mesh being
/// built (-1 if none), line() counts from 1 (0: the file as a whole, e.g. it cannot be opened).
class MeshFileError : public MeshError {
 public:
  MeshFileError(const std::string& what, std::string path, int line, int element = -1,
                int node = -1)
      : MeshError(what, element, node), path_(std::move(path)), line_(line) {}
  const std::string& path() const { return path_; }
  int line() const { return line_; }

 private:
  std::string path_;
  int line_;
};

/// Material constants that are not usable: E and rho must be positive and finite, the damping
/// non-negative and finite.
class MaterialError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// A mass-spring object (MassSpringSystem) that cannot be stepped: sizes that disagree, a
/// node mass that is not positive, a position or velocity that is not finite, a spring whose
/// nodes are out of range or whose rest length, stiffness or damping is not usable, or a
/// gravity, ground, contact (collision.hpp), wave speed or inelastic setting that is not
/// finite or out of range.
class ObjectError : public std::invalid_argument {
 public:
  ObjectError(const std::string& what, int node, int spring)
      : std::invalid_argument(what), node_(node), spring_(spring) {}
  int node() const { return node_; }      ///< the node at fault, -1 if none
  int spring() const { return spring_; }  ///< the spring at fault, -1 if none

 private:
  int node_, spring_;
};

/// The sparse linear solve of a backward Euler step failed: conjugate gradients did not reach
/// their tolerance, or the Cholesky factorization failed (the matrix is not positive definite
/// or not finite).
class LinearSolveError : public std::runtime_error {
 public:
  LinearSolveError(const std::string& what, int iterations, double residual, int unknowns)
      : std::runtime_error(what),
        iterations_(iterations),
        residual_(residual),
        unknowns_(unknowns) {}
  int iterations() const { return iterations_; }  ///< CG iterations (0 for Cholesky)
  double residual() const { return residual_; }   ///< CG relative residual |A x - b| / |b|
  int unknowns() const { return unknowns_; }

 private:
  int iterations_;
  double residual_;
  int unknowns_;
};

}  // namespace gencoord::deformable
