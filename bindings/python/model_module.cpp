// The Python module of one generated model. The build defines which:
//   GENCOORD_MODEL_HEADER  the generated header, e.g. "generated/double_pendulum.hpp"
//   GENCOORD_MODEL_CLASS   its struct, e.g. gencoord::models::DoublePendulum
//   GENCOORD_MODULE_NAME   the module's name, e.g. double_pendulum
#include "gencoord_python/bind_model.hpp"

#include GENCOORD_MODEL_HEADER

PYBIND11_MODULE(GENCOORD_MODULE_NAME, module) {
  gencoord::python::bind_model<GENCOORD_MODEL_CLASS>(module);
}
