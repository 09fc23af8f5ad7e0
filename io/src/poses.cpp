// io/src/poses.cpp: reading poses (JSON, the fast simdjson path, CSV) and turning them
// into kernel poses; writing them is io/src/poses_write.cpp.
#include <Eigen/Dense>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <qmotion/io/json_text.hpp>
#include <qmotion/io/poses.hpp>
#include <qmotion/io/robot_programs.hpp>
#include <qmotion/kernel/error.hpp>
#include <sstream>

#include "json_simd.hpp"
#ifdef QMOTION_WITH_CGAL
#include <qmotion/io/exact_number.hpp>
#endif
#include <qmotion/kernel/quaternion.hpp>

namespace qmotion::io {
namespace {

using json = nlohmann::json;

std::string pose_where(const std::string& source, std::size_t i, const std::string& field) {
  return source + ": pose " + std::to_string(i) + " (poses[" + std::to_string(i) + "]" +
         (field.empty() ? "" : "." + field) + ")";
}

/// Where a field of pose i is: "file: pose i (poses[i].field)".
struct Where {
  std::string source;
  std::size_t pose;
  std::string field;
  std::string str() const { return pose_where(source, pose, field); }
  Where operator/(const std::string& sub) const {
    return Where{source, pose, field.empty() ? sub : field + "." + sub};
  }
  Where at(std::size_t k) const {
    return Where{source, pose, field + "[" + std::to_string(k) + "]"};
  }
};

std::vector<Number> read_numbers(const json& j, std::size_t count, const Where& where) {
  if (!j.is_array())
    throw Error(Errc::invalid_input,
                where.str() + ": expected an array of " + std::to_string(count) + " numbers");
  if (j.size() != count)
    throw Error(Errc::invalid_input, where.str() + ": expected " + std::to_string(count) +
                                         " numbers, found " + std::to_string(j.size()));
  std::vector<Number> out;
  out.reserve(count);
  for (std::size_t k = 0; k < count; ++k)
    out.push_back(read_number_lazy(j[k], [&] { return where.at(k).str(); }));
  return out;
}

/// Checks one pose's rotation: non-zero quaternion, proper orthogonal matrix, non-zero axis.
void validate_rotation(const RotationInput& r, const Where& w) {
  const std::string where = w.str();
  switch (r.kind) {
    case RotationInput::Kind::quaternion: {
      double n = 0;
      for (const auto& v : r.values) n += v.value * v.value;
      if (!(n > 0))
        throw Error(Errc::invalid_input,
                    (w / "quaternion").str() + ": the zero quaternion is not a rotation");
      if (!std::isfinite(n))
        throw Error(Errc::invalid_input, (w / "quaternion").str() + ": components too large");
      break;
    }
    case RotationInput::Kind::matrix: {
      Eigen::Matrix3d m;
      for (int i = 0; i < 9; ++i) m(i / 3, i % 3) = r.values[static_cast<std::size_t>(i)].value;
      const double err = (m.transpose() * m - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
      if (!(err <= 1e-6))
        throw Error(Errc::invalid_input, (w / "matrix").str() + ": not orthogonal (|M^T M - I| = " +
                                             std::to_string(err) + " > 1e-6)");
      if (!(m.determinant() > 0))
        throw Error(
            Errc::invalid_input,
            (w / "matrix").str() + ": determinant is negative (a reflection, not a rotation)");
      break;
    }
    case RotationInput::Kind::axis_angle: {
      const double n = std::hypot(r.values[0].value, r.values[1].value, r.values[2].value);
      if (!(n > 0))
        throw Error(Errc::invalid_input,
                    (w / "axis_angle.axis").str() + ": the zero vector is not an axis");
      break;
    }
  }
}

[[noreturn]] void too_many_poses(const std::string& source) {
  throw Error(Errc::invalid_input,
              source + ": more than " + std::to_string(kMaxPoses) +
                  " poses (the limit keeps memory bounded: 10^5 poses take about 1 GB to "
                  "interpolate and 4 GB to sweep); split the motion");
}

void validate_set(PoseSet& set) {
  const auto& P = set.poses;
  if (P.size() < 2)
    throw Error(Errc::invalid_input, set.source +
                                         ": needs at least two poses to interpolate, found " +
                                         std::to_string(P.size()));
  const bool first_t = P.front().t.has_value();
  for (std::size_t i = 0; i < P.size(); ++i) {
    if (P[i].t.has_value() != first_t)
      throw Error(Errc::invalid_input, pose_where(set.source, i, "t") +
                                           ": t must be given for every pose or for none" +
                                           (first_t ? " (missing here)" : " (pose 0 has none)"));
    validate_rotation(P[i].rotation, Where{set.source, i, "rotation"});
  }
  if (first_t)
    for (std::size_t i = 1; i < P.size(); ++i)
      if (!(P[i].t->value > P[i - 1].t->value))
        throw Error(Errc::invalid_input,
                    pose_where(set.source, i, "t") +
                        ": parameters must increase strictly, but t = " + P[i].t->source() +
                        " follows t = " + P[i - 1].t->source());
}

RotationInput read_rotation(const json& r, const Where& w) {
  const std::string where = w.str();
  if (!r.is_object())
    throw Error(Errc::invalid_input,
                where + ": expected an object with quaternion, matrix or axis_angle");
  RotationInput out;
  int forms = 0;
  if (r.contains("quaternion")) {
    ++forms;
    out.kind = RotationInput::Kind::quaternion;
    out.values = read_numbers(r["quaternion"], 4, w / "quaternion");
  }
  if (r.contains("matrix")) {
    ++forms;
    const json& m = r["matrix"];
    if (!m.is_array() || m.size() != 3)
      throw Error(Errc::invalid_input, (w / "matrix").str() + ": expected 3 rows of 3 numbers");
    out.kind = RotationInput::Kind::matrix;
    out.values.clear();
    for (std::size_t i = 0; i < 3; ++i) {
      auto row = read_numbers(m[i], 3, (w / "matrix").at(i));
      out.values.insert(out.values.end(), row.begin(), row.end());
    }
  }
  if (r.contains("axis_angle")) {
    ++forms;
    const Where aw = w / "axis_angle";
    const json& aa = r["axis_angle"];
    out.kind = RotationInput::Kind::axis_angle;
    out.values = read_numbers(require(aa, "axis", aw.str()), 3, aw / "axis");
    out.values.push_back(read_number(require(aa, "angle_deg", aw.str()), (aw / "angle_deg").str()));
  }
  if (forms == 0)
    throw Error(Errc::invalid_input, where + ": needs one of quaternion, matrix, axis_angle");
  if (forms > 1)
    throw Error(Errc::invalid_input, where + ": give only one of quaternion, matrix, axis_angle");
  return out;
}

}  // namespace

bool is_known_unit(const std::string& u) {
  return u == "mm" || u == "cm" || u == "m" || u == "in" || u == "ft" || u == "um";
}

PoseSet parse_poses_json_value(const json& doc, const std::string& source) {
  PoseSet set;
  set.source = source;
  if (!doc.is_object())
    throw Error(Errc::invalid_input, source + ": expected a JSON object with a 'poses' array");
  if (doc.contains("units")) {
    if (!doc["units"].is_string() || !is_known_unit(doc["units"].get<std::string>()))
      throw Error(Errc::invalid_input, source + ": units: expected one of mm, cm, m, in, ft, um");
    set.units = doc["units"].get<std::string>();
  }
  const json& poses = require(doc, "poses", source);
  if (!poses.is_array()) throw Error(Errc::invalid_input, source + ": poses: expected an array");
  if (poses.size() > kMaxPoses) too_many_poses(source);
  set.poses.reserve(poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const json& p = poses[i];
    const std::string where = pose_where(source, i, "");
    if (!p.is_object()) throw Error(Errc::invalid_input, where + ": expected an object");
    PoseInput in;
    if (p.contains("t") && !p["t"].is_null())
      in.t = read_number_lazy(p["t"], [&] { return pose_where(source, i, "t"); });
    const auto pos = read_numbers(require(p, "position", where), 3, Where{source, i, "position"});
    std::copy(pos.begin(), pos.end(), in.position.begin());
    in.rotation = read_rotation(require(p, "rotation", where), Where{source, i, "rotation"});
    set.poses.push_back(std::move(in));
  }
  validate_set(set);
  return set;
}

namespace {
namespace sj = simd::sj;

/// Reads an array of exactly `n` numbers into `out`; false for anything else.
bool fast_numbers(sj::value v, std::size_t n, std::vector<Number>& out) {
  const std::size_t before = out.size();
  return simd::numbers(v, out, /*lean=*/true) && out.size() - before == n;
}

/// The rotation object: exactly one of its three forms, each key once; false otherwise.
bool fast_rotation(sj::value v, RotationInput& out) {
  sj::object r;
  if (v.get_object().get(r)) return false;
  int forms = 0;
  for (auto field : r) {
    std::string_view key;
    if (field.unescaped_key().get(key)) return false;
    sj::value fv = field.value();
    if (key == "quaternion") {
      out.kind = RotationInput::Kind::quaternion;
      if (++forms > 1 || !fast_numbers(fv, 4, out.values)) return false;
    } else if (key == "matrix") {
      out.kind = RotationInput::Kind::matrix;
      sj::array rows;
      if (++forms > 1 || fv.get_array().get(rows)) return false;
      std::size_t k = 0;
      for (auto row : rows) {
        sj::value rv;
        if (k++ == 3 || row.get(rv) || !fast_numbers(rv, 3, out.values)) return false;
      }
      if (k != 3) return false;
    } else if (key == "axis_angle") {
      out.kind = RotationInput::Kind::axis_angle;
      sj::object aa;
      if (++forms > 1 || fv.get_object().get(aa)) return false;
      bool axis = false, angle = false;
      Number angle_deg;
      for (auto af : aa) {
        std::string_view ak;
        if (af.unescaped_key().get(ak)) return false;
        sj::value av = af.value();
        if (ak == "axis") {
          if (axis || !fast_numbers(av, 3, out.values)) return false;
          axis = true;
        } else if (ak == "angle_deg") {
          if (angle || !simd::number(av, angle_deg, /*lean=*/true)) return false;
          angle = true;
        } else if (!simd::check(av)) {
          return false;
        }
      }
      if (!axis || !angle) return false;
      out.values.push_back(std::move(angle_deg));
    } else if (!simd::check(fv)) {
      return false;
    }
  }
  return forms == 1;
}

/// One pose object into `in`; false for anything the tree reader should word.
bool fast_pose(sj::value e, PoseInput& in) {
  sj::object p;
  if (e.get_object().get(p)) return false;
  bool t = false, position = false, rotation = false;
  for (auto pf : p) {
    std::string_view pk;
    if (pf.unescaped_key().get(pk)) return false;
    sj::value pv = pf.value();
    if (pk == "t") {
      bool null = false;
      if (t || pv.is_null().get(null)) return false;
      if (!null && !simd::number(pv, in.t.emplace(), /*lean=*/true)) return false;
      t = true;
    } else if (pk == "position") {
      std::vector<Number> xyz;
      if (position || !fast_numbers(pv, 3, xyz)) return false;
      std::move(xyz.begin(), xyz.end(), in.position.begin());
      position = true;
    } else if (pk == "rotation") {
      if (rotation || !fast_rotation(pv, in.rotation)) return false;
      rotation = true;
    } else if (!simd::check(pv, 3)) {
      return false;
    }
  }
  return position && rotation;
}

}  // namespace

std::optional<PoseSet> simd::poses_text(std::string_view text, const std::string& source) {
  std::vector<Member> root;
  if (!members(text, root)) return std::nullopt;
  PoseSet set;
  set.source = source;
  bool units = false, poses = false;
  for (const auto& [key, value] : root) {
    bool ok = true;
    if (key == "units") {
      ok = !units && string_value(value, set.units) && is_known_unit(set.units);
      units = true;
    } else if (key == "poses") {
      // Pose by pose: each pose's text is indexed alone (the shared parser), never the array;
      // counted first, so the set is allocated once.
      std::size_t count = 0;
      ok = !poses && elements(value, [&](std::string_view) { return ++count <= kMaxPoses; });
      if (ok) set.poses.reserve(count);
      ok = ok && elements(value, [&](std::string_view e) {
             return read_member(
                 e, [&](sj::value v) { return fast_pose(v, set.poses.emplace_back()); });
           });
      poses = true;
    } else {
      ok = check_slice(value, 1);
    }
    if (!ok) return std::nullopt;
  }
  if (!poses) return std::nullopt;
  validate_set(set);
  return set;
}

std::optional<PoseSet> parse_poses_fast(const std::string& text, const std::string& source) {
  const simd::Padded padded(text);
  return simd::poses_text(padded.view(), source);
}

PoseSet parse_poses_json(const std::string& text, const std::string& source) {
  if (auto set = parse_poses_fast(text, source)) return std::move(*set);
  return parse_poses_json_value(parse_json(text, source), source);
}

PoseSet parse_poses_csv(const std::string& text, const std::string& source) {
  PoseSet set;
  set.source = source;
  std::istringstream in(text);
  std::string line;
  std::vector<std::string> header;
  std::size_t line_no = 0;
  auto split = [](const std::string& s) {
    std::vector<std::string> cells;
    std::string cell;
    std::istringstream ls(s);
    while (std::getline(ls, cell, ',')) {
      const auto b = cell.find_first_not_of(" \t\r"), e = cell.find_last_not_of(" \t\r");
      cells.push_back(b == std::string::npos ? "" : cell.substr(b, e - b + 1));
    }
    if (!s.empty() && s.back() == ',') cells.emplace_back();
    return cells;
  };
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos ||
        line[line.find_first_not_of(" \t")] == '#')
      continue;
    const auto cells = split(line);
    const std::string where = source + ": line " + std::to_string(line_no);
    if (header.empty()) {
      header = cells;
      const std::vector<std::string> with_t = {"t", "x", "y", "z", "qw", "qx", "qy", "qz"};
      const std::vector<std::string> without_t(with_t.begin() + 1, with_t.end());
      if (header != with_t && header != without_t)
        throw Error(
            Errc::invalid_input,
            where + ": header must be 't,x,y,z,qw,qx,qy,qz' (t optional), found '" + line + "'");
      continue;
    }
    if (cells.size() != header.size())
      throw Error(Errc::invalid_input, where + " (pose " + std::to_string(set.poses.size()) +
                                           "): expected " + std::to_string(header.size()) +
                                           " values, found " + std::to_string(cells.size()));
    std::vector<Number> v;
    for (std::size_t k = 0; k < cells.size(); ++k)
      v.push_back(parse_number_text(cells[k], where + ", column '" + header[k] + "' (pose " +
                                                  std::to_string(set.poses.size()) + ")"));
    if (set.poses.size() == kMaxPoses) too_many_poses(source);
    PoseInput p;
    std::size_t o = 0;
    if (header.size() == 8) p.t = v[o++];
    for (std::size_t k = 0; k < 3; ++k) p.position[k] = v[o++];
    p.rotation.kind = RotationInput::Kind::quaternion;
    p.rotation.values.assign(v.begin() + static_cast<std::ptrdiff_t>(o), v.end());
    set.poses.push_back(std::move(p));
  }
  if (header.empty())
    throw Error(Errc::invalid_input,
                source + ": empty CSV file (expected the header t,x,y,z,qw,qx,qy,qz)");
  validate_set(set);
  return set;
}

PoseSet read_poses(const std::string& path) { return read_poses(path, RobotOptions{}); }

PoseSet read_poses(const std::string& path, const RobotOptions& robot) {
  const std::string text = read_text_file(path);
  const auto dot = path.rfind('.');
  std::string ext = dot == std::string::npos ? "" : path.substr(dot + 1);
  for (auto& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const bool program = ext == "src" || ext == "mod" || ext == "prg" || ext == "script";
  if (!program && (robot.given() || robot.skip_unknown))
    throw Error(Errc::invalid_input,
                path +
                    ": --robot-config, --tool, --base and --skip-unknown are for robot "
                    "programs (.src, .mod, .prg, .script)");
  RobotOptions o = robot;
  if (!o.config_text && !o.config_path.empty()) o.config_text = read_text_file(o.config_path);
  if (ext == "csv") return parse_poses_csv(text, path);
  if (ext == "src") {  // KUKA KRL, with the .dat beside it when there is one
    for (const char* dat : {".dat", ".DAT"}) {
      const std::string dat_path = path.substr(0, dot) + dat;
      std::error_code ec;
      if (std::filesystem::exists(dat_path, ec))
        return parse_krl(text, path, read_text_file(dat_path), dat_path, o);
    }
    return parse_krl(text, path, std::nullopt, {}, o);
  }
  if (ext == "mod" || ext == "prg") return parse_rapid(text, path, o);
  if (ext == "script") return parse_urscript(text, path, o);
  return parse_poses_json(text, path);
}

std::vector<Pose<double>> to_poses_double(const PoseSet& set) {
  std::vector<Pose<double>> out;
  out.reserve(set.poses.size());
  for (const auto& p : set.poses) {
    Pose<double> q;
    if (p.t) q.t = p.t->value;
    q.position = Eigen::Vector3d(p.position[0].value, p.position[1].value, p.position[2].value);
    const auto& v = p.rotation.values;
    switch (p.rotation.kind) {
      case RotationInput::Kind::quaternion:
        q.rotation = kernel::normalized(
            kernel::Quaternion<double>(v[0].value, v[1].value, v[2].value, v[3].value));
        break;
      case RotationInput::Kind::matrix: {
        Eigen::Matrix3d m;
        for (int i = 0; i < 9; ++i) m(i / 3, i % 3) = v[static_cast<std::size_t>(i)].value;
        // Project to the nearest rotation first (the file may round its entries).
        Eigen::JacobiSVD<Eigen::Matrix3d> svd(m, Eigen::ComputeFullU | Eigen::ComputeFullV);
        q.rotation = kernel::from_rotation_matrix(
            Eigen::Matrix3d(svd.matrixU() * svd.matrixV().transpose()));
        break;
      }
      case RotationInput::Kind::axis_angle:
        q.rotation = kernel::from_axis_angle(Eigen::Vector3d(v[0].value, v[1].value, v[2].value),
                                             v[3].value * M_PI / 180.0);
        break;
    }
    out.push_back(q);
  }
  return out;
}

#ifdef QMOTION_WITH_CGAL
std::vector<Pose<kernel::Rational>> to_poses_exact(const PoseSet& set) {
  std::vector<Pose<kernel::Rational>> out;
  for (std::size_t i = 0; i < set.poses.size(); ++i) {
    const auto& p = set.poses[i];
    if (p.rotation.kind != RotationInput::Kind::quaternion)
      throw Error(Errc::invalid_input,
                  pose_where(set.source, i, "rotation") +
                      ": exact mode needs the rotation as a quaternion (a rotation matrix or an "
                      "axis and angle has no exact rational quaternion in general)");
    Pose<kernel::Rational> q;
    if (p.t) q.t = exact_from_text(p.t->source());
    for (int k = 0; k < 3; ++k)
      q.position(k) = exact_from_text(p.position[static_cast<std::size_t>(k)].source());
    const auto& v = p.rotation.values;
    q.rotation = kernel::Quaternion<kernel::Rational>(
        exact_from_text(v[0].source()), exact_from_text(v[1].source()),
        exact_from_text(v[2].source()), exact_from_text(v[3].source()));
    out.push_back(q);
  }
  return out;
}

PoseSet with_quaternion_rotations(const PoseSet& set, std::vector<std::size_t>* replaced) {
  PoseSet out = set;
  const auto poses = to_poses_double(set);
  auto exact_text = [](double v) {
    std::ostringstream os;
    os << kernel::Rational(v);  // "p/q" with q a power of two: the double's exact value
    return Number{os.str(), v};
  };
  for (std::size_t i = 0; i < set.poses.size(); ++i) {
    if (set.poses[i].rotation.kind == RotationInput::Kind::quaternion) continue;
    const auto& q = poses[i].rotation;
    out.poses[i].rotation =
        RotationInput{RotationInput::Kind::quaternion,
                      {exact_text(q.w()), exact_text(q.x()), exact_text(q.y()), exact_text(q.z())}};
    if (replaced) replaced->push_back(i);
  }
  return out;
}
#endif

}  // namespace qmotion::io
