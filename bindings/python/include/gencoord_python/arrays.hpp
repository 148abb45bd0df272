// SPDX-License-Identifier: BSD-3-Clause
// NumPy arrays in and out of the kernels: the checks that name the argument and the shape it
// needs, and the copy between NumPy's row-major arrays and Eigen's column-major matrices.
//
// Every input is read as float64 (float32 and integer arrays are converted; complex, boolean
// and object arrays are refused), every output is float64: the kernels run in double.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace gencoord::python {

namespace py = pybind11;

/// Contiguous row-major float64.
using Float64Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// "(2,)", "(N, 2)": a shape as NumPy prints it.
inline std::string shape_text(const std::vector<py::ssize_t>& shape) {
  std::string text = "(";
  for (std::size_t k = 0; k < shape.size(); ++k) text += (k ? ", " : "") + std::to_string(shape[k]);
  return text + (shape.size() == 1 ? ",)" : ")");
}

/// `value` as contiguous float64, or ValueError naming `name` and what it should have been.
inline Float64Array float64_array(py::handle value, const std::string& name,
                                  const std::string& expected) {
  py::array array = py::array::ensure(value);
  if (!array)
    throw py::value_error(name + ": expected " + expected + " of real numbers, got " +
                          std::string(py::str(py::type::of(value))));
  const char kind = array.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u')
    throw py::value_error(name + ": expected " + expected +
                          " of real numbers (float64 or float32), got dtype " +
                          std::string(py::str(array.dtype())));
  return Float64Array::ensure(array);
}

/// A vector input of a kernel: one vector of `size` entries, or a batch of N of them.
struct VectorInput {
  Float64Array data;
  py::ssize_t batch = -1;  // -1: one vector, shape (size,); else shape (batch, size)
  py::ssize_t size = 0;

  const double* row(py::ssize_t i) const { return data.data() + (batch < 0 ? 0 : i * size); }
};

/// ValueError naming the first entry of `array` that is NaN or infinite: a state, an input or
/// a time must be finite in every entry point alike (the kernels would return NaN for it
/// where rhs and simulate raise).
inline void require_finite(const Float64Array& array, const std::string& name) {
  const double* data = array.data();
  const py::ssize_t count = array.size();
  for (py::ssize_t k = 0; k < count; ++k) {
    if (std::isfinite(data[k])) continue;
    std::string where = name;
    if (array.ndim() == 2)
      where += "[" + std::to_string(k / array.shape(1)) + ", " +
               std::to_string(k % array.shape(1)) + "]";
    else if (array.ndim() == 1) where += "[" + std::to_string(k) + "]";
    throw py::value_error(where + " is " + std::string(py::str(py::float_(data[k]))) +
                          ": expected finite numbers");
  }
}

inline VectorInput vector_input(py::handle value, const std::string& name, py::ssize_t size) {
  const std::string expected =
      "an array of shape " + shape_text({size}) + " or (N, " + std::to_string(size) + ")";
  VectorInput input{float64_array(value, name, expected), -1, size};
  const py::array& array = input.data;
  if (array.ndim() == 2 && array.shape(1) == size) input.batch = array.shape(0);
  if (input.batch >= 0 || (array.ndim() == 1 && array.shape(0) == size)) {
    require_finite(input.data, name);
    return input;
  }
  std::vector<py::ssize_t> shape(array.shape(), array.shape() + array.ndim());
  throw py::value_error(name + ": expected " + expected + ", got shape " + shape_text(shape));
}

/// An Eigen vector of a model's fixed size from `size` doubles.
template <class Vector>
Vector to_vector(const double* values) {
  Vector vector;
  for (Eigen::Index k = 0; k < vector.rows(); ++k) vector(k) = values[k];
  return vector;
}

/// Shape and copy of one kernel result: a scalar, an Eigen vector (its rows), or an Eigen
/// matrix (rows x columns), written row-major.
template <class Value, class = void>
struct Result {
  static std::vector<py::ssize_t> shape() {
    const Value value;  // fixed-size, or a HeapMatrix at its size
    if constexpr (Value::ColsAtCompileTime == 1) return {value.rows()};
    return {value.rows(), value.cols()};
  }
  static void copy(const Value& value, double* out) {
    for (Eigen::Index r = 0; r < value.rows(); ++r)
      for (Eigen::Index c = 0; c < value.cols(); ++c) *out++ = value(r, c);
  }
};

template <class Value>
struct Result<Value, std::enable_if_t<std::is_arithmetic_v<Value>>> {
  static std::vector<py::ssize_t> shape() { return {}; }
  static void copy(Value value, double* out) { *out = static_cast<double>(value); }
};

/// A fixed-size kernel result kept two-dimensional even with one column: the input matrix
/// of a one-input model is (nq, 1), as B is.
template <class Matrix>
struct AsMatrix {
  Matrix value;
};

template <class Matrix>
struct Result<AsMatrix<Matrix>> {
  static std::vector<py::ssize_t> shape() {
    return {Matrix::RowsAtCompileTime, Matrix::ColsAtCompileTime};
  }
  static void copy(const AsMatrix<Matrix>& matrix, double* out) {
    Result<Matrix>::copy(matrix.value, out);
  }
};

/// A float64 array of shape (batch, *shape), or `shape` when batch < 0.
inline py::array_t<double> output_array(py::ssize_t batch, std::vector<py::ssize_t> shape) {
  if (batch >= 0) shape.insert(shape.begin(), batch);
  return py::array_t<double>(shape);
}

/// A float64 array of shape (rows, cols) holding a copy of a dynamic-size matrix.
inline py::array_t<double> matrix_array(const Eigen::MatrixXd& matrix) {
  py::array_t<double> array(
      {static_cast<py::ssize_t>(matrix.rows()), static_cast<py::ssize_t>(matrix.cols())});
  Result<Eigen::MatrixXd>::copy(matrix, array.mutable_data());
  return array;
}

/// A float64 array of shape (size,) holding a copy of a vector.
inline py::array_t<double> vector_array(const Eigen::VectorXd& vector) {
  py::array_t<double> array(static_cast<py::ssize_t>(vector.size()));
  std::copy(vector.data(), vector.data() + vector.size(), array.mutable_data());
  return array;
}

/// A read-only float64 array holding a copy of `values`.
template <class Container>
py::array_t<double> read_only_array(const Container& values) {
  py::array_t<double> array(static_cast<py::ssize_t>(values.size()));
  std::copy(values.begin(), values.end(), array.mutable_data());
  array.attr("setflags")(py::arg("write") = false);
  return array;
}

}  // namespace gencoord::python
