// tests/bench/occt_convert.hpp: our NURBS as OpenCASCADE geometry, for the benchmarks that
// hand the same curve or surface to OpenCASCADE (io/ keeps its own conversion private:
// no OpenCASCADE type in its headers).
#pragma once
#include <qmotion/io/occt.hpp>
#include <qmotion/sweep/nurbs.hpp>
#include <vector>

// clang-format off
#include <Geom_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <STEPControl_Writer.hxx>
#include <StepData_Protocol.hxx>
#include <StepData_StepWriter.hxx>
#include <XSControl_WorkSession.hxx>
// clang-format on
#include <fstream>
#include <string>

namespace qmotion::bench {

/// A full clamped knot vector as OpenCASCADE's 1-based distinct knots and multiplicities.
struct OcctKnots {
  TColStd_Array1OfReal knots;
  TColStd_Array1OfInteger mults;
  explicit OcctKnots(const std::vector<double>& full) : knots(1, 1), mults(1, 1) {
    std::vector<double> k;
    std::vector<int> m;
    io::knots_to_distinct(full, k, m);
    knots.Resize(1, static_cast<int>(k.size()), Standard_False);
    mults.Resize(1, static_cast<int>(k.size()), Standard_False);
    for (std::size_t i = 0; i < k.size(); ++i) {
      knots.SetValue(static_cast<int>(i) + 1, k[i]);
      mults.SetValue(static_cast<int>(i) + 1, m[i]);
    }
  }
};

inline Handle(Geom_BSplineCurve) to_occt(const sweep::NurbsCurve<double>& c) {
  const int n = static_cast<int>(c.points.size());
  TColgp_Array1OfPnt P(1, n);
  TColStd_Array1OfReal W(1, n);
  for (int i = 0; i < n; ++i) {
    const auto& p = c.points[static_cast<std::size_t>(i)];
    P.SetValue(i + 1, gp_Pnt(p.x(), p.y(), p.z()));
    W.SetValue(i + 1, c.weights[static_cast<std::size_t>(i)]);
  }
  const OcctKnots K(c.knots);
  return new Geom_BSplineCurve(P, W, K.knots, K.mults, c.degree);
}

inline Handle(Geom_BSplineSurface) to_occt(const sweep::NurbsSurface<double>& s) {
  const int nu = static_cast<int>(s.points.size()), nv = static_cast<int>(s.points[0].size());
  TColgp_Array2OfPnt P(1, nu, 1, nv);
  TColStd_Array2OfReal W(1, nu, 1, nv);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const auto& p = s.points[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
      P.SetValue(i + 1, j + 1, gp_Pnt(p.x(), p.y(), p.z()));
      W.SetValue(i + 1, j + 1, s.weights[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)]);
    }
  const OcctKnots U(s.knots_u), V(s.knots_v);
  return new Geom_BSplineSurface(P, W, U.knots, V.knots, U.mults, V.mults, s.degree_u, s.degree_v);
}

/// Prints the writer's model as STEPControl_Writer::Write does (StepData_StepWriter) but with
/// the 17 significant digits io::write_step writes ("%.17E"): OpenCASCADE alone, our numbers.
inline bool print_step17(STEPControl_Writer& w, const std::string& path) {
  StepData_StepWriter sw(w.Model());
  sw.FloatWriter().SetFormat("%.17E");
  sw.SendModel(Handle(StepData_Protocol)::DownCast(w.WS()->Protocol()));
  std::ofstream f(path, std::ios::binary);
  return f && sw.Print(f);
}

}  // namespace qmotion::bench
