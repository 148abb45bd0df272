// SPDX-License-Identifier: BSD-3-Clause
// The floor under one call of a model module's qddot, for bench/python_lambdify.py. It holds
// what no binding can avoid, measured apart:
//   bare_qddot(q, v) -> (seconds, checksum)  the same kernel over N states from C++, no Python
//   empty(q, v) -> array(nq)                 a pybind11 function with the call's signature
//                                            (two float64 vectors in, a new vector out) that
//                                            does nothing
// The script compiles this file with the module's own compile command (defining the same
// GENCOORD_MODEL_HEADER and GENCOORD_MODEL_CLASS), so the kernel is compiled identically.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <chrono>
#include <stdexcept>
#include <utility>

#include "gencoord/model/model_traits.hpp"

#include GENCOORD_MODEL_HEADER

namespace py = pybind11;
using Model = GENCOORD_MODEL_CLASS;
using Vector = py::array_t<double, py::array::c_style | py::array::forcecast>;

namespace {

std::pair<double, double> bare_qddot(const Vector& q, const Vector& v) {
  if (q.ndim() != 2 || q.shape(1) != Model::nq || v.ndim() != 2 || v.shape(0) != q.shape(0) ||
      v.shape(1) != Model::nq) {
    throw std::invalid_argument("bare_qddot: q and v must have shape (N, nq)");
  }
  const gencoord::ParamsOf<Model> params;
  const double* q_data = q.data();
  const double* v_data = v.data();
  double checksum = 0.0;  // keeps the compiler from dropping the calls
  const auto start = std::chrono::steady_clock::now();
  for (py::ssize_t i = 0; i < q.shape(0); ++i) {
    const gencoord::QVec<Model> qi =
        Eigen::Map<const gencoord::QVec<Model>>(q_data + i * Model::nq);
    const gencoord::QVec<Model> vi =
        Eigen::Map<const gencoord::QVec<Model>>(v_data + i * Model::nq);
    checksum += Model::qddot(qi, vi, 0.0, params)(0);
  }
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
  return {elapsed.count(), checksum};
}

}  // namespace

PYBIND11_MODULE(GENCOORD_MODULE_NAME, module) {
  module.def("bare_qddot", &bare_qddot, py::arg("q"), py::arg("v"));
  module.def(
      "empty", [](const Vector& q, const Vector&) { return Vector(q.size()); }, py::arg("q"),
      py::arg("v"));
}
