// <qmotion/sweep/self_intersection_proof.hpp>: what the self-intersection prover
// (<qmotion/sweep/self_intersection.hpp>) established, and where, in words for messages.
#pragma once
#include <cstddef>
#include <optional>
#include <sstream>
#include <string>

namespace qmotion::sweep {

/// What the proof established. `none`: no two points of the surfaces (and caps) coincide,
/// proven. `crossing` / `touching`: two parts of the surface came within `eps` of each other
/// (crossing when their normals differ by more than 1e-3 rad there, touching when parallel).
/// `singular`: the surface's derivatives are dependent at a point (a profile point that does
/// not move, say: one profile point found at one place at two t), where injectivity cannot be
/// shown. `undecided`: the budget ran out, or a
/// weight is not positive.
struct SelfIntersectionProof {
  enum class Status { none, crossing, touching, singular, undecided };
  Status status = Status::undecided;
  /// Where (for any status but none): the parameter box of the first part, and of the second
  /// for contacts; `cap` names an end cap (0: at the first t, 1: at the last) as the second.
  struct Place {
    double t0 = 0, t1 = 0;
    std::size_t edge = 0;
    double v0 = 0, v1 = 0;
  };
  Place first, second;
  std::optional<int> cap;
  std::string reason;       ///< for undecided
  std::size_t patches = 0;  ///< rational Bezier patches of the surfaces
  std::size_t pairs = 0;    ///< patch pairs examined (parts of patches, after subdivision)
  std::size_t cells = 0;    ///< parts of patches made by subdivision
  int depth = 0;            ///< deepest subdivision (halvings of a patch)
  double eps = 0;           ///< the contact distance (1e-9 of the size)
  bool proven() const { return status == Status::none; }

  static const char* name(Status s) {
    switch (s) {
      case Status::none:
        return "none";
      case Status::crossing:
        return "crossing";
      case Status::touching:
        return "touching";
      case Status::singular:
        return "singular";
      case Status::undecided:
        return "undecided";
    }
    return "undecided";
  }
  /// "t in [a, b] on profile edge e, v in [c, d]" for a place.
  static std::string where(const Place& p) {
    std::ostringstream os;
    os.precision(6);
    os << "t in [" << p.t0 << ", " << p.t1 << "], profile edge " << p.edge << " v in [" << p.v0
       << ", " << p.v1 << "]";
    return os.str();
  }
  /// What follows "the sweep " in a message.
  std::string describe() const {
    std::ostringstream os;
    os.precision(3);
    switch (status) {
      case Status::none:
        os << "is proven free of self-intersection (" << patches << " Bezier patches, " << pairs
           << " pairs examined, subdivided to depth " << depth << ")";
        break;
      case Status::crossing:
      case Status::touching:
        os << (status == Status::crossing ? "crosses itself" : "touches itself") << " within "
           << eps << ": " << where(first) << " meets "
           << (cap ? std::string(*cap == 0 ? "the first end cap" : "the last end cap")
                   : where(second));
        break;
      case Status::singular:
        os << "is not proven free of self-intersection: the surface is singular near "
           << where(first)
           << " (a profile point standing still, or the surface's derivatives dependent there)";
        break;
      case Status::undecided:
        os << "is not proven free of self-intersection: " << reason;
        break;
    }
    return os.str();
  }
};

}  // namespace qmotion::sweep
