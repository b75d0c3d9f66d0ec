// Shared declarations of the Python bindings (one file per group of types).
#pragma once

#include <pybind11/pybind11.h>

#include <string>

namespace superdex::python {

namespace py = pybind11;

void BindParams(py::module_& m);
void BindScene(py::module_& m);

/// Raises ValueError(message) when message is not empty.
inline void CheckValue(const std::string& message) {
  if (!message.empty()) throw py::value_error(message);
}

}  // namespace superdex::python
