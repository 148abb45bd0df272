// SPDX-License-Identifier: BSD-3-Clause
// A model's Params as a Python class: one attribute per parameter, with the model file's name,
// default and description, settable by keyword in the constructor.
#pragma once

#include <pybind11/pybind11.h>

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "gencoord/model/model_traits.hpp"

namespace gencoord::python {

namespace py = pybind11;

namespace detail {

template <class M>
double& parameter(ParamsOf<M>& params, std::size_t k) {
  return *params.find(M::parameter_names[k]);
}

// A parameter's value from Python: a finite number, else a ValueError naming the parameter.
inline double parameter_value(const std::string& name, py::handle value) {
  double number = 0.0;
  try {
    number = value.cast<double>();
  } catch (const py::cast_error&) {
    throw py::value_error(name + ": expected a number, got " + std::string(py::repr(value)));
  }
  if (!std::isfinite(number))
    throw py::value_error(name + ": expected a finite number, got " + std::string(py::repr(value)));
  return number;
}

template <class M>
std::string names_list() {
  std::string list;
  for (const char* name : M::parameter_names)
    list += (list.empty() ? "" : ", ") + std::string(name);
  return list.empty() ? "none" : list;
}

}  // namespace detail

template <class M>
void bind_params(py::module_& module) {
  using Params = ParamsOf<M>;
  std::string doc = std::string("Parameters of ") + M::name +
                    "; the defaults are the model file's. Params(name=value, ...) sets some.";
  for (std::size_t k = 0; k < M::parameter_names.size(); ++k)
    doc += std::string("\n  ") + M::parameter_names[k] + ": " + M::parameter_descriptions[k];
  // module-local: two modules of one model each have their own class
  py::class_<Params> params(module, "Params", py::module_local(), doc.c_str());
  params.def(py::init([](const py::kwargs& values) {
               Params p;
               for (const auto& [key, value] : values) {
                 const std::string name = py::str(key);
                 double* slot = p.find(name);
                 if (!slot)
                   throw py::type_error(std::string(M::name) + ": no parameter called '" + name +
                                        "'; the parameters are " + detail::names_list<M>());
                 *slot = detail::parameter_value(name, value);
               }
               return p;
             }),
             "Params(name=value, ...): the defaults, with the named parameters set");
  for (std::size_t k = 0; k < M::parameter_names.size(); ++k) {
    params.def_property(
        M::parameter_names[k], [k](Params& p) { return detail::parameter<M>(p, k); },
        [k](Params& p, py::handle value) {
          detail::parameter<M>(p, k) = detail::parameter_value(M::parameter_names[k], value);
        },
        M::parameter_descriptions[k]);
  }
  params.def("__repr__", [](Params& p) {
    std::string text = "Params(";
    for (std::size_t k = 0; k < M::parameter_names.size(); ++k)
      text += std::string(k ? ", " : "") + M::parameter_names[k] + "=" +
              std::string(py::repr(py::float_(detail::parameter<M>(p, k))));
    return text + ")";
  });
  params.def("__eq__", [](Params& a, Params& b) {
    for (std::size_t k = 0; k < M::parameter_names.size(); ++k)
      if (detail::parameter<M>(a, k) != detail::parameter<M>(b, k)) return false;
    return true;
  });
  params.def(
      "to_dict",
      [](Params& p) {
        py::dict values;
        for (std::size_t k = 0; k < M::parameter_names.size(); ++k)
          values[M::parameter_names[k]] = detail::parameter<M>(p, k);
        return values;
      },
      "The parameters as a dict, in the model file's order");
  params.def("__copy__", [](const Params& p) { return Params(p); });
}

}  // namespace gencoord::python
