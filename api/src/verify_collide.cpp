// api/src/verify_collide.cpp: verify's holder collisions, every move in parallel
// (docs/guide/verify.md, "Collisions").
#include "verify_collide.hpp"

#include <tbb/parallel_for.h>

#include <memory>
#include <vector>

namespace qmotion::detail {
namespace {

const char* verdict(cam::Contact::Kind k) {
  return k == cam::Contact::Kind::contact ? "contact" : "undecided";
}

/// A move's first contact with `with`, as listed in the report.
nlohmann::json contact_json(const cam::Program& program, std::size_t i, const cam::Contact& c,
                            const char* with) {
  nlohmann::json j;
  j["block"] = i;
  j["line"] = program.moves[i].line;
  j["move"] = move_name(program.moves[i].kind);
  j["with"] = with;
  j["found"] = verdict(c.kind);
  j["t"] = {c.t_lo, c.t_hi};
  if (c.kind == cam::Contact::Kind::contact) {
    j["point"] = {c.point.x(), c.point.y(), c.point.z()};
    j["depth_at_least"] = c.depth;
  }
  return j;
}

/// Appends what is not clear to `list`; `first` becomes the earliest contact.
void gather(const cam::Program& program, std::size_t i, const cam::Contact& c, const char* with,
            nlohmann::json& list, nlohmann::json& first, std::size_t& cells,
            const char* body = nullptr) {
  cells += c.cells;
  if (c.kind == cam::Contact::Kind::clear) return;
  nlohmann::json j = contact_json(program, i, c, with);
  if (body) j["body"] = body;
  if (c.kind == cam::Contact::Kind::contact &&
      (first.is_null() || (first["block"] == i && c.t_hi < first["t"][1].get<double>())))
    first = j;
  list.push_back(std::move(j));
}

}  // namespace

nlohmann::json holder_collisions(const cam::Program& program, const sweep::Body& cutter,
                                 const HolderSections& holder, const sweep::Body& part,
                                 const std::optional<cam::Stock>& stock, const cam::CutIndex* cut,
                                 double tol, std::size_t& cells) {
  const std::vector<cam::detail::Core> body = cam::holder_cores(holder, cutter.L);
  cam::Stock part_target;
  part_target.body = std::make_shared<sweep::Body>(part);
  const std::size_t n = program.moves.size();
  std::vector<cam::Contact> with_stock(n), with_part(n);
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
    const cam::Move& m = program.moves[i];
    with_part[i] = cam::first_contact(m, i, body, part_target, nullptr, tol);
    if (stock) with_stock[i] = cam::first_contact(m, i, body, *stock, cut, tol);
  });
  nlohmann::json list = nlohmann::json::array(), first;
  for (std::size_t i = 0; i < n; ++i) {
    gather(program, i, with_stock[i], "stock", list, first, cells);
    gather(program, i, with_part[i], "part", list, first, cells);
  }
  nlohmann::json out;
  nlohmann::json sections = nlohmann::json::array();
  for (const auto& [r, h] : holder) sections.push_back({{"radius", r}, {"length", h}});
  out["holder"] = {{"sections", sections}, {"from", cutter.L}};
  if (holder.size() == 1) {
    out["holder"]["radius"] = holder[0].first;
    out["holder"]["length"] = holder[0].second;
  }
  out["against"] = stock ? nlohmann::json{"stock as cut so far", "part"} : nlohmann::json{"part"};
  out["first"] = first;
  out["contacts"] = list;
  out["clear"] = list.empty();
  return out;
}

nlohmann::json rapids_through_stock(const cam::Program& program, const sweep::Body& cutter,
                                    const cam::Stock& stock, const cam::CutIndex& cut, double tol,
                                    std::size_t& cells) {
  const std::vector<cam::detail::Core> body = cam::detail::cores_of(cutter);
  std::vector<std::size_t> rapids;
  for (std::size_t i = 0; i < program.moves.size(); ++i)
    if (program.moves[i].kind == cam::Move::Kind::traverse) rapids.push_back(i);
  std::vector<cam::Contact> found(rapids.size());
  tbb::parallel_for(std::size_t(0), rapids.size(), [&](std::size_t k) {
    const std::size_t i = rapids[k];
    double covered = 0;  // the move before came straight down the tool's axis
    if (i > 0) {
      const cam::Move& p = program.moves[i - 1];
      if (p.kind != cam::Move::Kind::arc && p.from.x() == p.to.x() && p.from.y() == p.to.y() &&
          p.from.z() >= p.to.z())
        covered = p.from.z() - p.to.z();
    }
    found[k] = cam::first_contact(program.moves[i], i, body, stock, &cut, tol, true, covered);
  });
  nlohmann::json list = nlohmann::json::array(), first;
  for (std::size_t k = 0; k < rapids.size(); ++k)
    gather(program, rapids[k], found[k], "stock", list, first, cells);
  return list;
}

nlohmann::json fixture_collisions(const cam::Program& program, const sweep::Body& cutter,
                                  const std::optional<HolderSections>& holder,
                                  const std::vector<cam::Stock>& fixtures, double tol,
                                  std::size_t& cells) {
  std::vector<std::pair<std::vector<cam::detail::Core>, const char*>> bodies{
      {cam::detail::cores_of(cutter), "cutter"}};
  if (holder) bodies.emplace_back(cam::holder_cores(*holder, cutter.L), "holder");
  const std::size_t n = program.moves.size(), per = fixtures.size() * bodies.size();
  std::vector<cam::Contact> found(n * per);
  tbb::parallel_for(std::size_t(0), n * per, [&](std::size_t k) {
    const std::size_t i = k / per, f = k % per / bodies.size(), b = k % bodies.size();
    found[k] = cam::first_contact(program.moves[i], i, bodies[b].first, fixtures[f], nullptr, tol);
  });
  nlohmann::json list = nlohmann::json::array(), first;
  for (std::size_t k = 0; k < found.size(); ++k) {
    const std::size_t i = k / per, f = k % per / bodies.size(), b = k % bodies.size();
    const std::string with = "fixture " + std::to_string(f + 1);
    gather(program, i, found[k], with.c_str(), list, first, cells, bodies[b].second);
  }
  return {{"first", first}, {"contacts", list}, {"clear", list.empty()}};
}

}  // namespace qmotion::detail
