// SPDX-License-Identifier: BSD-3-Clause
// The Python module of one generated model. The build defines which:
//   GENCOORD_MODEL_HEADER  the generated header, e.g. "generated/double_pendulum.hpp"
//   GENCOORD_MODEL_CLASS   its struct, e.g. gencoord::models::DoublePendulum
//   GENCOORD_MODULE_NAME   the module's name, e.g. double_pendulum
//   GENCOORD_BUILT_FOR     the interpreter it was built for, e.g. "/usr/bin/python3"
#include <string>

#include "gencoord_python/bind_model.hpp"

#include GENCOORD_MODEL_HEADER

#define GENCOORD_STRINGIFY_(x) #x
#define GENCOORD_STRINGIFY(x) GENCOORD_STRINGIFY_(x)

namespace {

// Another interpreter of the same ABI (a virtual environment's beside Debian's) can load the
// module; where it lacks NumPy, say which interpreter the module was built for.
void require_numpy() {
  try {
    pybind11::module_::import("numpy");
  } catch (pybind11::error_already_set&) {
    const std::string running = pybind11::str(pybind11::module_::import("sys").attr("executable"));
    throw pybind11::import_error(
        std::string(GENCOORD_STRINGIFY(GENCOORD_MODULE_NAME)) + ": this interpreter (" + running +
        ") cannot import numpy, which the module needs; it was built by gencoord python for " +
        GENCOORD_BUILT_FOR + " (Python " PY_VERSION "): run that one, or install NumPy here " +
        "(Debian: python3-numpy) and rebuild with gencoord python MODEL --python " + running);
  }
}

}  // namespace

PYBIND11_MODULE(GENCOORD_MODULE_NAME, module) {
  require_numpy();
  gencoord::python::bind_model<GENCOORD_MODEL_CLASS>(module);
}
