// SPDX-License-Identifier: BSD-3-Clause
// The runtime's errors as Python exceptions of the model's module. StepSizeError and every
// std::invalid_argument reach Python as ValueError (pybind11's translation).
#pragma once

#include <pybind11/pybind11.h>

#include "gencoord/errors.hpp"

namespace gencoord::python {

namespace py = pybind11;

/// Module-local, so that several model modules in one interpreter each raise their own.
inline void bind_errors(py::module_& module) {
  py::register_local_exception<DynamicsError>(module, "DynamicsError", PyExc_RuntimeError);
  py::register_local_exception<NewtonError>(module, "NewtonError", PyExc_RuntimeError);
  py::register_local_exception<DivergedError>(module, "DivergedError", PyExc_RuntimeError);
}

}  // namespace gencoord::python
