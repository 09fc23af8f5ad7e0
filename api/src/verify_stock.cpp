// api/src/verify_stock.cpp: the stock a program leaves on the part, over the part's whole
// surface, and its map (docs/guide/verify.md, "Stock left").
#include "verify_stock.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <qmotion/kernel/outward.hpp>

namespace qmotion::detail {
namespace {

using kernel::down;
using kernel::up;

/// A triangle of the part's surface and the value v = min(depth in the raw stock, distance
/// to the swept cutter) at its centre: v_lo <= v <= v_hi there, and v is 1-Lipschitz, so
/// over the cell it lies within rho (the centre's farthest corner) of that.
struct Cell {
  Eigen::Vector3d a, b, c;
  double area = 0, rho = 0;
  double depth = 0;  ///< in the raw stock, at the centre
  double v_lo = 0, v_hi = 0;
  /// A bound of v over the whole cell (evaluate): the box stock's depth, and the nearest
  /// straight move's distance at the corners (it is convex).
  double v_max = HUGE_VAL;
  std::size_t move = 0;
  double t = 0;
  bool cut = false;  ///< a move comes nearer than the stock's outside
  bool settled = true;

  Eigen::Vector3d centre() const { return (a + b + c) / 3; }
  double top() const { return std::max(std::min(up(v_hi + rho), v_max), 0.0); }  ///< at most
  double bottom() const { return std::max(down(v_lo - rho), 0.0); }  ///< stock left, at least
  double inside_lo() const { return depth - rho > 0 ? area : 0; }    ///< area in the stock
  double inside_hi() const { return std::min(depth + rho, v_max) > 0 ? area : 0; }
};

/// The value at x within eps (1e-12 relative for the stock's depth), with where the cutter
/// comes nearest. Past the stock (depth <= 0) no move is searched: the value is the depth.
cam::CutIndex::Near value_at(const cam::CutIndex& cut, const cam::Stock& stock,
                             const Eigen::Vector3d& x, double eps, double& depth) {
  depth = stock.depth(x);
  const double slack = cam::detail::margin(x);
  cam::CutIndex::Near n;
  if (depth > 0) {
    n = cut.distance(x, eps, depth, true);
  } else {
    n.lower = n.upper = depth;
  }
  n.lower = std::min(n.lower, down(depth - slack));
  n.upper = std::min(n.upper, up(depth + slack));
  return n;
}

void evaluate(Cell& cell, const cam::CutIndex& cut, const cam::Program& program,
              const cam::Stock& stock, double tol, std::size_t& queries) {
  const Eigen::Vector3d g = cell.centre();
  cell.rho =
      up(std::max({(cell.a - g).norm(), (cell.b - g).norm(), (cell.c - g).norm()}) * (1 + 1e-15));
  // A cell far wider than tol serves the mean, whose bound is wider by rho anyway.
  const double eps = std::max(tol / 4, cell.rho / 2);
  const cam::CutIndex::Near n = value_at(cut, stock, g, eps, cell.depth);
  cell.v_lo = n.lower;
  cell.v_hi = n.upper;
  cell.move = n.move;
  cell.t = n.t;
  cell.cut = n.upper < cell.depth;
  cell.settled = n.settled;
  queries += n.queries;
  cell.area = 0.5 * (cell.b - cell.a).cross(cell.c - cell.a).norm();
  const double slack = cam::detail::margin(g);
  cell.v_max = up(stock.depth_max(cell.a, cell.b, cell.c) + slack);
  if (cell.cut && program.moves[cell.move].kind != cam::Move::Kind::arc)
    cell.v_max = std::min(
        cell.v_max, std::max({cut.move_upper(cell.move, cell.a), cut.move_upper(cell.move, cell.b),
                              cut.move_upper(cell.move, cell.c)}));
}

/// The four halves of a cell by its edges' midpoints.
std::array<Cell, 4> split(const Cell& p) {
  const Eigen::Vector3d ab = 0.5 * (p.a + p.b), bc = 0.5 * (p.b + p.c), ca = 0.5 * (p.c + p.a);
  std::array<Cell, 4> q;
  q[0].a = p.a, q[0].b = ab, q[0].c = ca;
  q[1].a = ab, q[1].b = p.b, q[1].c = bc;
  q[2].a = ca, q[2].b = bc, q[2].c = p.c;
  q[3].a = ab, q[3].b = bc, q[3].c = ca;
  return q;
}

struct Totals {
  double max_lo = 0, max_hi = 0, sum_lo = 0, sum_hi = 0, area_lo = 0, area_hi = 0;
  double sum_mid = 0, area_mid = 0;
  std::size_t best = 0;
  bool settled = true;

  double mean_lo() const { return area_hi > 0 ? std::max(down(sum_lo / area_hi), 0.0) : 0; }
  double mean_hi() const { return area_lo > 0 ? std::min(up(sum_hi / area_lo), max_hi) : max_hi; }
};

Totals totals(const std::vector<Cell>& cells) {
  Totals t;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const Cell& c = cells[i];
    const double lo = std::max(c.v_lo, 0.0);
    if (i == 0 || lo > t.max_lo) {
      t.max_lo = lo;
      t.best = i;
    }
    t.max_hi = std::max(t.max_hi, c.top());
    t.sum_lo += c.area * c.bottom();
    t.sum_hi += c.area * c.top();
    t.area_lo += c.inside_lo();
    t.area_hi += c.inside_hi();
    if (c.depth > 0) {
      t.sum_mid += c.area * std::max(c.v_hi, 0.0);  // a value reached (v_lo is a bound)
      t.area_mid += c.area;
    }
    t.settled = t.settled && c.settled;
  }
  t.sum_lo = down(t.sum_lo * (1 - 1e-12));
  t.sum_hi = up(t.sum_hi * (1 + 1e-12));
  t.area_lo = down(t.area_lo * (1 - 1e-12));
  t.area_hi = up(t.area_hi * (1 + 1e-12));
  return t;
}

/// The cells to split next: those that may hold more than the largest found plus tol, and
/// once those are settled and while the mean is wider than tol, those that widen it most:
/// up to `room` for the largest and `mean_room` for the mean.
std::vector<std::size_t> to_split(const std::vector<Cell>& cells, const Totals& t, double tol,
                                  std::size_t room, std::size_t mean_room) {
  std::vector<std::size_t> pick;
  for (std::size_t i = 0; i < cells.size() && pick.size() < room; ++i)
    if (cells[i].top() > t.max_lo + tol) pick.push_back(i);
  // The mean's cells once the largest is settled, and only while a round can still split
  // an eighth of them: few rounds.
  if (!pick.empty() || t.mean_hi() - t.mean_lo() <= tol || mean_room < cells.size() / 8)
    return pick;
  auto weight = [&](const Cell& c) {
    return c.area * (c.top() - c.bottom()) + (c.inside_hi() - c.inside_lo()) * t.max_hi;
  };
  std::vector<std::size_t> rest;
  for (std::size_t i = 0; i < cells.size(); ++i)
    if (!(cells[i].top() > t.max_lo + tol) && weight(cells[i]) > 0) rest.push_back(i);
  const std::size_t n = std::min(rest.size(), mean_room);
  std::partial_sort(
      rest.begin(), rest.begin() + static_cast<std::ptrdiff_t>(n), rest.end(),
      [&](std::size_t a, std::size_t b) { return weight(cells[a]) > weight(cells[b]); });
  pick.insert(pick.end(), rest.begin(), rest.begin() + static_cast<std::ptrdiff_t>(n));
  return pick;
}

}  // namespace

StockLeft stock_left(const cam::Program& program, const cam::CutIndex& cut, const sweep::Body& part,
                     const cam::Stock& stock, double tol) {
  const sweep::TriangleMesh& mesh = part.mesh;
  std::vector<Cell> cells(mesh.triangles.size());
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const auto& t = mesh.triangles[i];
    cells[i].a = mesh.vertices[static_cast<std::size_t>(t[0])];
    cells[i].b = mesh.vertices[static_cast<std::size_t>(t[1])];
    cells[i].c = mesh.vertices[static_cast<std::size_t>(t[2])];
  }
  std::vector<std::size_t> queries(cells.size(), 0);
  tbb::parallel_for(std::size_t(0), cells.size(), [&](std::size_t i) {
    evaluate(cells[i], cut, program, stock, tol, queries[i]);
  });
  StockLeft s;
  s.queries = std::accumulate(queries.begin(), queries.end(), std::size_t(0));
  s.cells = cells.size();
  Totals t = totals(cells);
  const std::size_t budget = cells.size() + kStockCells;
  const std::size_t mean_budget = cells.size() + kStockMeanCells;
  while (true) {
    const std::size_t room = (budget - std::min(budget, s.cells)) / 3;
    const std::size_t mean_room = (mean_budget - std::min(mean_budget, s.cells)) / 3;
    const std::vector<std::size_t> pick =
        to_split(cells, t, tol, std::min(room, cells.size()), std::min(mean_room, cells.size()));
    if (pick.empty()) break;
    std::vector<Cell> fresh(3 * pick.size());
    for (std::size_t k = 0; k < pick.size(); ++k) {
      const std::array<Cell, 4> q = split(cells[pick[k]]);
      cells[pick[k]] = q[0];
      for (int j = 1; j < 4; ++j)
        fresh[3 * k + static_cast<std::size_t>(j) - 1] = q[static_cast<std::size_t>(j)];
    }
    std::vector<std::size_t> round(pick.size() + fresh.size(), 0);
    tbb::parallel_for(std::size_t(0), round.size(), [&](std::size_t i) {
      Cell& c = i < pick.size() ? cells[pick[i]] : fresh[i - pick.size()];
      evaluate(c, cut, program, stock, tol, round[i]);
    });
    s.queries += std::accumulate(round.begin(), round.end(), std::size_t(0));
    s.cells += fresh.size();
    cells.insert(cells.end(), fresh.begin(), fresh.end());
    t = totals(cells);
  }
  s.max_lower = t.max_lo;
  s.max_upper = std::max(t.max_hi, t.max_lo);
  s.max_settled = t.settled && s.max_upper - s.max_lower <= tol;
  s.mean_lower = std::min(t.mean_lo(), t.mean_hi());
  s.mean_upper = t.mean_hi();
  s.mean_settled = t.settled && s.mean_upper - s.mean_lower <= tol;
  s.mean_estimate = t.area_mid > 0 ? t.sum_mid / t.area_mid : 0;
  s.area_in_stock = t.area_mid;
  if (!cells.empty()) {
    const Cell& best = cells[t.best];
    s.point = best.centre();
    if (best.cut) {
      s.block = best.move;
      s.line = program.moves[best.move].line;
      s.t = best.t;
    }
  }
  s.vertex_values.resize(mesh.vertices.size());
  tbb::parallel_for(std::size_t(0), mesh.vertices.size(), [&](std::size_t i) {
    const Eigen::Vector3d& x = mesh.vertices[i];
    const double depth = stock.depth(x);
    const cam::CutIndex::Near n = cut.distance(x, tol / 4, std::max(depth, 2 * tol));
    const double d = std::min(0.5 * (n.lower + n.upper), std::max(depth, 0.0));
    // Entered by the cutter: the (negative) distance; else the stock left, 0 past the stock.
    s.vertex_values[i] = d < 0 ? d : std::max(d, 0.0);
  });
  return s;
}

nlohmann::json stock_json(const StockLeft& s) {
  nlohmann::json j;
  j["max"] = {s.max_lower, s.max_upper};
  j["max_certified"] = s.max_settled;
  nlohmann::json at;
  at["point"] = {s.point.x(), s.point.y(), s.point.z()};
  if (s.block) {
    at["block"] = *s.block;
    at["line"] = s.line;
    at["t"] = s.t;
    at["nearest"] = "cutter";
  } else {
    at["nearest"] = "raw stock";
  }
  j["where"] = at;
  j["mean"] = {s.mean_lower, s.mean_upper};
  j["mean_certified"] = s.mean_settled;
  j["mean_estimate"] = s.mean_estimate;
  j["area_in_stock"] = s.area_in_stock;
  j["cells"] = s.cells;
  j["distance_queries"] = s.queries;
  return j;
}

}  // namespace qmotion::detail
