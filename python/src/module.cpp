// The `superdex` Python module: the spec's API in snake_case over the C++ library.
#include "bindings.h"

PYBIND11_MODULE(superdex, m) {
  m.doc() =
      "superdex: a simulator for contact-rich scenes on a compliant contact model.\n\n"
      "Units are SI throughout (m, kg, s, N, Pa). Build a Scene, add actors, step or run it;\n"
      "states and trajectories come back as numpy arrays. Bad values raise ValueError with the\n"
      "field and the rule; a stage that does not converge raises RuntimeError.";
  superdex::python::BindParams(m);
  superdex::python::BindSoft(m);
  superdex::python::BindScene(m);
  superdex::python::BindFit(m);
}
