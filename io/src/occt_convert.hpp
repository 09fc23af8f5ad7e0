// io/src/occt_convert.hpp: what the STEP/IGES writer and reader share (private to io/):
// qmotion's NURBS as OpenCASCADE's B-spline curves and surfaces and back, profile edges from
// an OpenCASCADE shape, unit names, and OpenCASCADE's messenger kept off stdout.
#pragma once
#include <Geom_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_Curve.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TopoDS_Shape.hxx>
#include <qmotion/sweep/nurbs.hpp>
#include <string>
#include <vector>

namespace qmotion::io::detail {

/// Our unit names -> STEP (write.step.unit) and IGES (unit name) spellings, and the size
/// of the unit in millimetres.
struct UnitNames {
  const char* step;
  const char* iges;
  double mm;
};

UnitNames unit_names(const std::string& unit);

/// OpenCASCADE's translators report statistics through the default messenger, which
/// prints to stdout; qmotion's stdout carries JSON, so the printers go (once).
void quiet_occt();

/// STEPControl_Controller::Init and IGESControl_Controller::Init: OpenCASCADE's translator
/// tables, editors and parameters, made once and kept for the process's lifetime (OpenCASCADE
/// frees none of them). In a build with AddressSanitizer these two calls run with leak
/// tracking off: they are the only allocations the leak checker is told to ignore by name,
/// since its fast unwinder cannot walk OpenCASCADE's frames to match a suppression there
/// (docs/testing.md, "Leaks").
void init_step_translator();
void init_iges_translator();

/// Numbers and integers as OpenCASCADE's 1-based arrays.
TColStd_Array1OfReal occt_reals(const std::vector<double>& v);
TColStd_Array1OfInteger occt_ints(const std::vector<int>& v);

/// A full knot vector as OpenCASCADE's distinct knots and their multiplicities.
struct OcctKnots {
  TColStd_Array1OfReal knots;
  TColStd_Array1OfInteger mults;
};

OcctKnots occt_knots(const std::vector<double>& full);

/// qmotion's NURBS as OpenCASCADE's B-spline surface and curve (weights kept, knots as
/// distinct values and multiplicities).
Handle(Geom_BSplineSurface) make_surface(const sweep::NurbsSurface<double>& s);
Handle(Geom_BSplineCurve) make_curve(const sweep::NurbsCurve<double>& c);

/// The faces as one open shell whose neighbours share an edge wherever their boundary
/// curves are the same data, bit for bit, on opposite sides (occt_shell.cpp): a surface cut
/// at its knots. A null shape when that does not join them (a degenerate side, a boundary
/// shared otherwise, borders that meet end to end without being equal): sewing's case.
TopoDS_Shape shared_edge_shell(const std::vector<sweep::NurbsSurface<double>>& faces);

/// OpenCASCADE's B-spline surface and curve as qmotion's NURBS (full knot vectors).
sweep::NurbsSurface<double> from_occt(Handle(Geom_BSplineSurface) g);
sweep::NurbsCurve<double> from_occt(Handle(Geom_BSplineCurve) g);

/// The shape of a STEP (ext .step, .stp) or IGES (.igs, .iges) file, lengths in unit u;
/// `file_units` gets the unit the file declares. prechecks: refuse a file whose entities
/// failed to load (it may crash the transfer). Errc::invalid_input naming path when it
/// cannot be read. Runs OpenCASCADE's parser: call it in a child process (isolated.hpp).
TopoDS_Shape read_shape(const std::string& path, const std::string& ext, const UnitNames& u,
                        bool prechecks, std::string& file_units);

/// How many distinct subshapes of the kind the shape has (a shared edge counts once).
int distinct(const TopoDS_Shape& shape, TopAbs_ShapeEnum kind);

/// Every edge of the shape but degenerate ones bounds exactly two faces (a closed shell).
bool closed_shape(const TopoDS_Shape& shape);

/// The text in lower case (file extensions).
std::string lower(std::string s);

/// The B-spline of curve on [first, last] (the curve itself when that is its whole range).
Handle(Geom_BSplineCurve) whole_curve(const Handle(Geom_Curve) & curve, double first, double last);

/// The profile edges of a shape as NURBS curves in order: the first wire's edges in wire
/// order (reversed edges reversed), or, without a wire, every edge chained end to start
/// (an edge is reversed where that joins it). Consecutive edges on one curve (a reader's
/// split at C0 knots) are joined back into that curve.
std::vector<sweep::NurbsCurve<double>> profile_edges(const TopoDS_Shape& shape);

}  // namespace qmotion::io::detail
