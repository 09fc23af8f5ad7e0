// io/src/robot_text.hpp: what the robot-program readers (KRL, RAPID, URScript) share: statements
// with where they start, refusals that name them, numbers, aggregates split at their commas,
// and rigid frames to map poses between tools and bases.
#pragma once
#include <Eigen/Geometry>
#include <qmotion/io/robot_programs.hpp>
#include <qmotion/kernel/error.hpp>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace qmotion::io::robot {

std::string upper(std::string_view s);
std::string trim(std::string_view s);

/// The non-empty lines of a program (1-based numbers), trimmed, each cut at `comment` outside
/// double quotes (and single quotes too with `single_quotes`).
std::vector<std::pair<int, std::string>> code_lines(const std::string& text, char comment,
                                                    bool single_quotes = false);

/// A statement and where it starts: "file: line N".
struct Statement {
  std::string text;
  std::string where;

  /// "line N", for messages that name a second statement beside the first.
  std::string line() const { return where.substr(where.rfind("line")); }
};

[[noreturn]] inline void refuse(const Statement& s, const std::string& why) {
  throw Error(Errc::invalid_input, s.where + ": " + why);
}

/// A statement the reader does not know: refused, or with options.skip_unknown a warning in
/// `set` naming the line.
void unknown(const Statement& s, const std::string& why, const RobotOptions& options, PoseSet& set);

/// The statement quoted for a message (at most 60 characters).
std::string construct(const std::string& text);

/// A number with its text; refuses anything else, naming `what`.
Number number(const std::string& token, const Statement& s, const std::string& what);

/// Splits at commas outside brackets, braces, parentheses and double quotes.
std::vector<std::string> split_top(std::string_view s);

/// True when `s` is an identifier (a letter or '_', then letters, digits and '_').
bool identifier(std::string_view s);

/// A rigid frame: x -> q x + p.
struct Frame {
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  Eigen::Vector3d p = Eigen::Vector3d::Zero();

  Frame operator*(const Frame& o) const { return {q * o.q, p + q * o.p}; }
  Frame inverse() const {
    const Eigen::Quaterniond c = q.conjugate();
    return {c, -(c * p)};
  }
};

/// The frame of a pose as a reader made it (a quaternion rotation).
Frame frame_of(const PoseInput& pose);
/// A pose of computed numbers (no source text) for a frame.
PoseInput pose_of(const Frame& f);
/// A pose with position `p` (numbers as read) and rotation q (computed).
PoseInput quaternion_pose(const std::array<Number, 3>& p, const Eigen::Quaterniond& q);

/// The set, refused when it has fewer than two poses or more than a pose file may hold.
PoseSet finished(PoseSet set, const std::string& source, const char* instructions);

}  // namespace qmotion::io::robot
