// The extension module breastfit._breastfit (imported by python/breastfit/__init__.py).
#include "bindings.h"

PYBIND11_MODULE(_breastfit, m) {
  using namespace breastfit::python;
  m.doc() = "breastfit: registration of a rigged template torso to breast scans (C++ extension; "
            "import breastfit, not this module).";
  register_exceptions(m);
  bind_mesh_io(m);
  bind_template(m);
  bind_register(m);
  bind_transfer(m);
  bind_cohort(m);
  bind_landmarks(m);
}
