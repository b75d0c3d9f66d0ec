// superdex._superdex, the compiled part of the Python package `superdex` (python/superdex/ re-exports
// it): the spec's API in snake_case over the C++ library.
#include "bindings.h"
#include "scenes/version.h"

PYBIND11_MODULE(_superdex, m) {
  m.doc() =
      "superdex: a simulator for contact-rich scenes on a compliant contact model.\n\n"
      "Units are SI throughout (m, kg, s, N, Pa). Build a Scene, add actors, step or run it;\n"
      "states and trajectories come back as numpy arrays. Bad values raise ValueError with the\n"
      "field and the rule; a stage that does not converge raises RuntimeError.";
  m.attr("__version__") = superdex::kVersion;  // the CMake project version, as `superdex --version`
  using namespace superdex::python;
  BindParams(m);
  BindTetMesh(m);
  BindSoftActorDesc(m);
  BindShellActorDesc(m);
  BindRigidShape(m);
  BindRigidActorDesc(m);
  BindStepReport(m);
  BindActorContactParams(m);
  BindActor(m);
  BindSceneState(m);
  BindArticulatedDescs(m);
  BindSceneClass(m);
  BindSceneFile(m);
  BindForwardSensitivity(m);
  BindFitting(m);
  BindRunSummary(m);
  BindRunScene(m);
  BindLoadSceneText(m);
}
