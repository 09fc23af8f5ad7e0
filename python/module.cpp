// python/module.cpp: the Python module `qmotion` (pybind11). Thin, like the CLI: every
// function converts its arguments, calls the library and converts the result.
// qmotion::Error becomes ValueError (bad input, exit 2), ArithmeticError (numerical
// failure, exit 3) or RuntimeError, with the CLI's message.
#include "convert.hpp"

namespace py = pybind11;
namespace qm = qmotion;

PYBIND11_MODULE(qmotion, m) {
  m.doc() =
      "qmotion: rational rigid-body motions (Juttler's dual-quaternion Bezier and B-spline "
      "motions) and their exact NURBS trajectories and kinematic sweep surfaces, written as "
      "STEP, IGES and JSON.\n\n"
      "    import qmotion\n"
      "    m = qmotion.interpolate('poses.json')          # elliptic + TR, like the CLI\n"
      "    s = qmotion.sweep(m, 'circle:3')[0]            # NurbsSurface, numpy arrays\n"
      "    qmotion.export(m, 'tube.step', profile='circle:3', solid=True)\n"
      "    qmotion.check('tube.step', m, profile='circle:3')['relative_deviation']\n\n"
      "Bad input raises ValueError, a numerical failure ArithmeticError, with the messages "
      "of the qmotion command line.";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const qm::Error& e) {
      switch (e.code()) {
        case qm::Errc::invalid_input:
          PyErr_SetString(PyExc_ValueError, e.what());
          return;
        case qm::Errc::numerical_failure:
          PyErr_SetString(PyExc_ArithmeticError, e.what());
          return;
        default:
          PyErr_SetString(PyExc_RuntimeError, e.what());
          return;
      }
    }
  });

  qm::python::bind_geometry(m);
  qm::python::bind_motion(m);
  qm::python::bind_jobs(m);
  qm::python::bind_pictures(m);
  qm::python::bind_values(m);
}
