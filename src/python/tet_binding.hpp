// fdrmesh._core._tetrahedralize: the 3D mesher (fdr::tetrahedralize) from numpy arrays.
#pragma once
#include <pybind11/pybind11.h>

namespace fdr::python {

void bind_tetrahedralize(pybind11::module_& mod);

}  // namespace fdr::python
