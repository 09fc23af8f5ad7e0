// api/src/verify_collide.hpp: verify's holder collisions (docs/guide/verify.md,
// "Collisions").
#pragma once
#include <nlohmann/json.hpp>
#include <optional>
#include <qmotion/cam/collision.hpp>
#include <qmotion/sweep/body.hpp>
#include <vector>

namespace qmotion::detail {

/// "G0", "G1" or "arc", as the report names a move.
inline const char* move_name(cam::Move::Kind k) {
  return k == cam::Move::Kind::traverse ? "G0" : k == cam::Move::Kind::feed ? "G1" : "arc";
}

/// A holder: cylinders (radius, length) stacked upwards from the cutter's length.
using HolderSections = std::vector<std::pair<double, double>>;

/// The holder (sections above the cutter's length) against the stock as cut so far
/// (when there is a stock; `cut` is what the program cuts) and the part, every move: each move's
/// first contact, certified, in program order, and the first of all. Counts the cells in `cells`.
nlohmann::json holder_collisions(const cam::Program& program, const sweep::Body& cutter,
                                 const HolderSections& holder, const sweep::Body& part,
                                 const std::optional<cam::Stock>& stock, const cam::CutIndex* cut,
                                 double tol, std::size_t& cells);

/// The cutter on every rapid move (G0) against the stock as cut so far: each one's first
/// contact, as holder_collisions lists them.
nlohmann::json rapids_through_stock(const cam::Program& program, const sweep::Body& cutter,
                                    const cam::Stock& stock, const cam::CutIndex& cut, double tol,
                                    std::size_t& cells);

/// The cutter, and the holder when given, against each fixture (never cut) over every
/// move: each move's first contact, as holder_collisions lists them, `with` naming the
/// fixture ("fixture 1", ...) and `body` the cutter or the holder.
nlohmann::json fixture_collisions(const cam::Program& program, const sweep::Body& cutter,
                                  const std::optional<HolderSections>& holder,
                                  const std::vector<cam::Stock>& fixtures, double tol,
                                  std::size_t& cells);

}  // namespace qmotion::detail
