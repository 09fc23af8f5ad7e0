// <qmotion/io/bodies.hpp>: bodies of the moving space given as text or as a mesh file
// (docs/formats.md, "Bodies").
#pragma once
#include <qmotion/sweep/body.hpp>
#include <string>

namespace qmotion::cam {
struct Stock;  // <qmotion/cam/stock.hpp>
}

namespace qmotion::io {

/// The deflection (mm) within which a STEP or IGES solid is meshed unless the caller says.
inline constexpr double kCadDeflection = 0.01;

/// The body named by `spec`: `sphere:r`, `box:a,b,c`, `cylinder:r,h`, `cutter:flat,D,L`,
/// `cutter:ball,D,L`, `cutter:bull,D,rc,L`, a triangle mesh file (.stl binary or ASCII, .obj,
/// .ply ASCII or binary little-endian) in the motion's unit, or a STEP or IGES solid, meshed
/// by OpenCASCADE within `cad_deflection` (io::mesh_cad). Errc::invalid_input naming the body
/// and what is wrong: an unknown kind, a bad or non-positive size, rc > D/2, a mesh that is
/// empty, open, non-manifold or inconsistently oriented, and the solids mesh_cad refuses.
sweep::Body read_body(const std::string& spec, double cad_deflection = kCadDeflection);

/// Whether `spec` names a STEP or IGES file (.step, .stp, .igs, .iges), which read_body and
/// read_stock mesh within their cad_deflection.
bool is_cad_file(const std::string& spec);

/// A body from a triangle mesh already in memory (the Python module's arrays), named
/// `label` in messages, indexed for distance queries. Errc::invalid_input for a vertex that
/// is not finite, a triangle naming a vertex that does not exist, and the meshes
/// require_closed_oriented refuses.
sweep::Body mesh_body(sweep::TriangleMesh mesh, const std::string& label);

/// Refuses (Errc::invalid_input naming `label`) a mesh that is not closed, 2-manifold and
/// consistently oriented (every directed edge must occur once and its reverse once), or
/// that is oriented inward or encloses no volume (its signed volume is not positive).
void require_closed_oriented(const sweep::TriangleMesh& m, const std::string& label);

/// A raw stock for `verify --stock` (or a fixture, `option` naming it in messages):
/// `box:x0,y0,z0,x1,y1,z1` (two opposite corners, in any order, mm), or a closed mesh file or
/// a STEP or IGES solid as read_body reads it. Errc::invalid_input naming the stock for
/// another body, bad numbers, and a box with an edge not longer than 0.
cam::Stock read_stock(const std::string& spec, const std::string& option = "--stock",
                      double cad_deflection = kCadDeflection);

}  // namespace qmotion::io
