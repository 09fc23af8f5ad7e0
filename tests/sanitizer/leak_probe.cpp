// tests/sanitizer/leak_probe.cpp: the leak checker's own test (docs/testing.md, "Leaks").
// Writes a bilinear patch as STEP and as IGES into the folder argv[1], which makes
// OpenCASCADE's process-lifetime translator tables; with "leak", it then leaks the
// OpenCASCADE surface that qmotion makes of the same patch. Under tests/sanitizer/lsan.supp,
// sanitizer.no_leak_without_one expects no leak reported without "leak", and
// sanitizer.leak_is_reported expects the leak reported with it: the runs differ only there.
#include <cstdio>
#include <cstring>
#include <qmotion/io/occt.hpp>
#include <string>

#include "occt_convert.hpp"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: leak_probe FOLDER [leak]\n");
    return 2;
  }
  const std::string folder = argv[1];
  qmotion::sweep::NurbsSurface<double> s;
  s.degree_u = s.degree_v = 1;
  s.knots_u = s.knots_v = {0, 0, 1, 1};
  s.points = {{{0, 0, 0}, {0, 1, 0}}, {{1, 0, 0}, {1, 1, 0.5}}};
  s.weights = {{1, 1}, {1, 1}};
  qmotion::io::write_step(folder + "/patch.step", s, {});
  qmotion::io::write_iges(folder + "/patch.igs", s, {});
  if (argc > 2 && std::strcmp(argv[2], "leak") == 0) {
    const Handle(Geom_BSplineSurface) surface = qmotion::io::detail::make_surface(s);
    surface->IncrementRefCounter();  // one owner too many: the surface is never freed
    std::puts("leaked the surface");
    std::fflush(stdout);  // the leak checker ends the process with _exit
  }
  return 0;
}
