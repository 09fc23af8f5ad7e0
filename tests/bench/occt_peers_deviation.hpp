// tests/bench/occt_peers_deviation.hpp: how far a route's surface, read back from its STEP
// file, is from the exact motion-applied profile (tests/bench/occt_peers.cpp): dense samples
// both ways, nearest seeds from a k-d tree, Gauss-Newton, never OpenCASCADE's projection.
#pragma once
#include <vector>

#include "occt_peers_case.hpp"
// clang-format off
#include <Geom_Surface.hxx>
#include <TopoDS_Shape.hxx>
// clang-format on

namespace qmotion::bench {

struct OcctFace {
  Handle(Geom_Surface) s;
  double u0, u1, v0, v1;
};

/// The faces of a shape with their surfaces and UV bounds.
std::vector<OcctFace> faces_of(const TopoDS_Shape& shape);

/// Samples along the motion for a case of this many spans.
int sample_count(int spans);

/// The Hausdorff distance between the faces and the exact surface, both ways, from samples at
/// most 1/resolution of the case's diagonal apart.
double deviation(const Case& c, const std::vector<OcctFace>& faces, int resolution);

/// The exact route's deviation at equal parameters: the surface read back at (t, s) against
/// M(t) c(s) (an upper bound of the geometric distance).
double parametric_deviation(const Case& c, const OcctFace& f);

}  // namespace qmotion::bench
