// api/src/verify.cpp: `qmotion verify`: a program's gouges, certified over every move
// (docs/guide/verify.md).
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <qmotion/api/verify.hpp>
#include <qmotion/io/atomic_file.hpp>
#include <qmotion/io/bodies.hpp>
#include <qmotion/io/gcode.hpp>
#include <qmotion/io/point_text.hpp>
#include <qmotion/kernel/error.hpp>

#include "verify_collide.hpp"
#include "verify_stock.hpp"

namespace qmotion {
namespace {

nlohmann::json where_json(const MoveGouge& g) {
  nlohmann::json j;
  j["block"] = g.block;
  j["line"] = g.line;
  j["move"] = detail::move_name(g.kind);
  j["depth"] = {g.gouge.lower, g.gouge.upper};
  j["t"] = g.gouge.t;
  j["point"] = {g.gouge.point.x(), g.gouge.point.y(), g.gouge.point.z()};
  return j;
}

sweep::Body read_cutter(const std::string& spec) {
  using K = sweep::Body::Kind;
  sweep::Body c = io::read_body(spec);
  sweep::validate(c);
  if (c.kind != K::flat_cutter && c.kind != K::ball_cutter && c.kind != K::bull_cutter)
    throw Error(Errc::invalid_input, "--tool '" + spec +
                                         "': verify needs a cutter (cutter:flat,D,L, "
                                         "cutter:ball,D,L or cutter:bull,D,rc,L)");
  return c;
}

sweep::Body read_part(const std::string& spec, double cad_deflection) {
  sweep::Body p = io::read_body(spec, cad_deflection);
  if (p.kind != sweep::Body::Kind::mesh)
    throw Error(Errc::invalid_input, "--part '" + spec +
                                         "': verify needs the part as a closed .stl, .obj or "
                                         ".ply mesh, or a STEP or IGES solid");
  return p;
}

/// --holder: cylinder:r,h, or holder:r1,h1,r2,h2,... (cylinders stacked upwards from the
/// cutter's length: a collet nut, then the chuck's body, ...).
detail::HolderSections read_holder(const std::string& spec) {
  const std::string where = "--holder '" + spec + "'";
  if (spec.rfind("holder:", 0) == 0) {
    const std::vector<double> v = io::parse_numbers(spec.substr(7), where);
    if (v.empty() || v.size() % 2 != 0)
      throw Error(Errc::invalid_input, where +
                                           ": expected holder:r1,h1,r2,h2,... (a radius and a "
                                           "length for each section, mm), got " +
                                           std::to_string(v.size()) + " numbers");
    detail::HolderSections sections;
    for (std::size_t k = 0; k < v.size(); k += 2) {
      if (!(v[k] > 0) || !(v[k + 1] > 0))
        throw Error(Errc::invalid_input, where + ": section " + std::to_string(k / 2 + 1) +
                                             " needs a positive radius and length");
      sections.emplace_back(v[k], v[k + 1]);
    }
    return sections;
  }
  const sweep::Body b = io::read_body(spec);
  if (b.kind != sweep::Body::Kind::cylinder)
    throw Error(Errc::invalid_input, where +
                                         ": the holder is a cylinder:r,h (radius, length; it "
                                         "starts at the cutter's length) or holder:r1,h1,r2,h2,... "
                                         "(sections stacked upwards)");
  return {{b.r, b.h}};
}

}  // namespace

nlohmann::json VerifyReport::report() const {
  nlohmann::json j;
  j["program"] = program;
  j["moves"] = {{"total", moves}, {"G0", traverses}, {"G1", feeds}, {"arcs", arcs}};
  j["tolerance"] = tolerance;
  if (cad_deflection) j["cad_deflection"] = *cad_deflection;
  nlohmann::json g;
  g["depth"] = {gouge_lower, gouge_upper};
  g["certified"] = settled;
  g["within_tolerance"] = settled && gouge_upper <= tolerance;
  g["never_touches"] = clear;
  if (deepest) g["deepest"] = where_json(*deepest);
  g["moves"] = nlohmann::json::array();
  for (const MoveGouge& m : gouges) g["moves"].push_back(where_json(m));
  j["gouge"] = g;
  // A rapid move that enters the part is a collision, whatever its depth.
  nlohmann::json c;
  c["checked"] = {"rapid moves (G0) through the part"};
  if (rapids_through_stock) {
    c["checked"].push_back("rapid moves (G0) through the stock as cut so far");
    c["rapids_through_stock"] = *rapids_through_stock;
  }
  if (fixtures) {
    c["checked"].push_back("the cutter and the holder against the fixtures");
    c["fixtures"] = *fixtures;
  }
  if (holder) {
    c["checked"].push_back("the holder against the stock as cut so far and the part");
    c["holder"] = *holder;
  }
  c["rapids_through_part"] = nlohmann::json::array();
  for (const MoveGouge& m : gouges)
    if (m.kind == cam::Move::Kind::traverse) c["rapids_through_part"].push_back(where_json(m));
  j["collisions"] = c;
  if (stock) j["stock_left"] = detail::stock_json(*stock);
  j["distance_queries"] = queries;
  j["seconds"] = seconds;
  return j;
}

VerifyReport verify(const VerifyOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  const double tol = o.tol.value_or(0.01);
  if (!(tol > 0) || !std::isfinite(tol))
    throw Error(Errc::invalid_input, "--tol: the tolerance must be a positive length in mm, got " +
                                         kernel::detail::format_double(tol));
  if (!o.output.empty() && io::lower_extension(o.output) != ".json")
    throw Error(Errc::invalid_input, "-o '" + o.output + "': the report is written as .json");
  if (!io::is_gcode_path(o.program))
    throw Error(Errc::invalid_input,
                "'" + o.program + "': verify reads G-code (.ngc, .nc, .gcode, .tap, .cnc)");
  const cam::Program program = io::read_gcode(o.program);
  const auto rotary = std::find_if(program.moves.begin(), program.moves.end(),
                                   [](const cam::Move& m) { return m.abc_from != m.abc_to; });
  if (rotary != program.moves.end())
    throw Error(Errc::invalid_input, o.program + ": line " + std::to_string(rotary->line) +
                                         " turns a rotary axis (A, B or C): verify checks 3-axis "
                                         "programs so far");
  if (!o.map.empty()) {
    const std::string e = io::lower_extension(o.map);
    if (e != ".ply" && e != ".png" && e != ".svg")
      throw Error(Errc::invalid_input,
                  "--map '" + o.map + "': the map is written as .ply, .png or .svg");
    if (o.stock.empty())
      throw Error(Errc::invalid_input, "--map '" + o.map +
                                           "': the map shows the stock left: "
                                           "give the raw stock with --stock");
  }
  const sweep::Body cutter = read_cutter(o.tool);
  // STEP and IGES solids are meshed within T / 4 (docs/guide/verify.md, "Parts").
  const double cad = tol / 4;
  const sweep::Body part = read_part(o.part, cad);
  const std::optional<cam::Stock> stock =
      o.stock.empty() ? std::nullopt
                      : std::optional<cam::Stock>(io::read_stock(o.stock, "--stock", cad));
  std::vector<cam::Stock> fixtures;
  for (const std::string& f : o.fixtures) fixtures.push_back(io::read_stock(f, "--fixture", cad));
  const bool any_cad = io::is_cad_file(o.part) || io::is_cad_file(o.stock) ||
                       std::any_of(o.fixtures.begin(), o.fixtures.end(), io::is_cad_file);
  std::optional<detail::HolderSections> holder;
  if (!o.holder.empty()) holder = read_holder(o.holder);

  VerifyReport r;
  r.program = o.program;
  r.tolerance = tol;
  r.moves = program.moves.size();
  if (any_cad) r.cad_deflection = cad;
  std::vector<cam::Gouge> found(program.moves.size());
  tbb::parallel_for(std::size_t(0), program.moves.size(), [&](std::size_t i) {
    found[i] = cam::move_gouge(program.moves[i], cutter, part, tol);
  });
  for (std::size_t i = 0; i < found.size(); ++i) {
    const cam::Move& m = program.moves[i];
    (m.kind == cam::Move::Kind::traverse ? r.traverses
     : m.kind == cam::Move::Kind::feed   ? r.feeds
                                         : r.arcs)++;
    const cam::Gouge& g = found[i];
    const MoveGouge here{i, m.line, m.kind, g};
    r.queries += g.queries;
    r.settled = r.settled && g.settled;
    r.gouge_upper = std::max(r.gouge_upper, g.upper);
    r.clear = r.clear && g.clear;
    if (g.lower > 0) r.gouges.push_back(here);
    if (g.lower > r.gouge_lower) {
      r.gouge_lower = g.lower;
      r.deepest = here;
    }
  }
  // What the program cuts, for the stock left and the collisions with the stock.
  std::optional<cam::CutIndex> cut;
  if (stock) {
    cut.emplace(program, cutter);
    r.stock = detail::stock_left(program, *cut, part, *stock, tol);
    r.queries += r.stock->queries;
  }
  if (stock) {
    std::size_t cells = 0;
    r.rapids_through_stock =
        detail::rapids_through_stock(program, cutter, *stock, *cut, tol, cells);
    r.queries += cells;
  }
  if (holder) {
    std::size_t cells = 0;
    r.holder = detail::holder_collisions(program, cutter, *holder, part, stock,
                                         cut ? &*cut : nullptr, tol, cells);
    r.queries += cells;
  }
  if (!fixtures.empty()) {
    std::size_t cells = 0;
    r.fixtures = detail::fixture_collisions(program, cutter, holder, fixtures, tol, cells);
    r.queries += cells;
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // The map first: a report is written only once everything it names is.
  if (!o.map.empty()) detail::write_stock_map(o.map, part, *r.stock, tol);
  if (!o.output.empty()) io::write_file_atomic(o.output, r.report().dump(2) + "\n");
  return r;
}

}  // namespace qmotion
