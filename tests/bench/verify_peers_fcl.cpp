// The holder's first contact (docs/guide/verify.md, "Collisions") against FCL's continuous
// collision detection (Debian's libfcl-dev): a cylindrical holder carried along straight
// moves past a box of stock, the moves placed to enter the stock by 0.5 to 0.005 mm or to
// clear it by 0.005 to 0.5 mm over its top, beside a face, past a corner and in a plunge.
// The truth is worked out apart from both (tests/holder_truth.hpp).
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/narrowphase/continuous_collision.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <qmotion/cam/collision.hpp>
#include <random>
#include <string>
#include <vector>

#include "../holder_truth.hpp"
#include "verify_peers.hpp"

namespace qmotion::peers {
namespace {

using V3 = Eigen::Vector3d;

// The scene: stock [-50, 50]^2 x [-40, 0]; the holder r 10, h 40, from the cutter's length
// 30 up (mm).
constexpr double kR = 10, kH = 40, kL = 30, kTol = 0.01;
const Eigen::AlignedBox3d kStock(V3(-50, -50, -40), V3(50, 50, 0));

struct Case {
  const char* kind;
  V3 from, to;  ///< the cutter's tip
  double gap;   ///< < 0: into the stock by -gap; > 0: clear by gap
};

/// The first t in [0, 1] at which the holder is inside the stock, or -1.
double true_first_contact(const Case& c) {
  return test::cylinder_box_first_contact(c.from, c.to, kR, kL, kL + kH, kStock);
}

std::vector<Case> cases(int n) {
  std::mt19937 gen(53);
  std::uniform_real_distribution<double> u(0, 1);
  const double gaps[] = {-0.5, -0.05, -0.005, 0.005, 0.02, 0.5};
  const char* kinds[] = {"over the top", "beside a face", "past a corner", "plunge"};
  std::vector<Case> out;
  for (int i = 0; i < n; ++i) {
    Case c;
    c.kind = kinds[i % 4];
    c.gap = gaps[(i / 4) % 6];
    const double s = 20 + 60 * u(gen), e = 20 + 60 * u(gen), across = -30 + 60 * u(gen);
    if (i % 4 == 0) {  // across the top at the holder's bottom 0 - gap
      const double z = -kL + c.gap;
      c.from = V3(-50 - kR - s, across, z);
      c.to = V3(50 + kR + e, across, z);
    } else if (i % 4 == 1) {  // along the face y = 50 at r + gap
      const double y = 50 + kR + c.gap, z = -kL - 5 - 20 * u(gen);
      c.from = V3(-50 - s, y, z);
      c.to = V3(50 + e, y, z);
    } else if (i % 4 == 2) {  // the line x + y = 100 + sqrt 2 (r + gap), past (50, 50)
      const double off = (100 + std::sqrt(2.0) * (kR + c.gap)) / 2, z = -kL - 5 - 20 * u(gen);
      c.from = V3(off - s, off + s, z);
      c.to = V3(off + e, off - e, z);
    } else {  // down onto the top with the disc over the edge x = 50
      const double x = 50 + kR * (2 * u(gen) - 1);
      c.from = V3(x, across, 20 + s);
      c.to = V3(x, across, -kL + c.gap);
    }
    if (u(gen) < 0.5) std::swap(c.from, c.to);
    out.push_back(c);
  }
  return out;
}

struct Method {
  std::string what;
  double seconds = 0;
  int found = 0, missed = 0, false_contacts = 0, undecided = 0;
  double late_mm = 0;   ///< the largest distance along the move past the true first contact
  double early_mm = 0;  ///< the largest distance along the move before it
  bool aborted = false;
};

void tally(Method& m, double truth, bool contact, double t, double length) {
  if (truth < 0 && contact) ++m.false_contacts;
  if (truth >= 0 && !contact) ++m.missed;
  if (truth >= 0 && contact) {
    ++m.found;
    m.late_mm = std::max(m.late_mm, (t - truth) * length);
    m.early_mm = std::max(m.early_mm, (truth - t) * length);
  }
}

/// FCL over every case in a child process (some of its modes stop on an assertion inside its
/// GJK; the row then says so), the tallies handed back through a pipe.
template <class Setup>
Method run_fcl(const char* what, const std::vector<Case>& all, const std::vector<double>& truth,
               Setup setup) {
  Method m{what};
  int fds[2];
  if (::pipe(fds) != 0) return m;
  std::fflush(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(fds[0]);
    std::freopen("/dev/null", "w", stderr);
    fcl::ContinuousCollisionRequestd request;
    setup(request);
    const auto holder = std::make_shared<fcl::Cylinderd>(kR, kH);
    const auto box = std::make_shared<fcl::Boxd>(kStock.sizes());
    fcl::Transform3d at_box = fcl::Transform3d::Identity();
    at_box.translation() = kStock.center();
    Method c;
    const auto t0 = std::chrono::steady_clock::now();
    for (std::size_t i = 0; i < all.size(); ++i) {
      fcl::Transform3d a = fcl::Transform3d::Identity(), b = fcl::Transform3d::Identity();
      a.translation() = all[i].from + V3(0, 0, kL + kH / 2);
      b.translation() = all[i].to + V3(0, 0, kL + kH / 2);
      fcl::ContinuousCollisionResultd result;
      fcl::continuousCollide<double>(holder.get(), a, b, box.get(), at_box, at_box, request,
                                     result);
      tally(c, truth[i], result.is_collide, result.time_of_contact,
            (all[i].to - all[i].from).norm());
    }
    const double v[6] = {seconds_since(t0),        double(c.found), double(c.missed),
                         double(c.false_contacts), c.late_mm,       c.early_mm};
    const bool ok = ::write(fds[1], v, sizeof v) == static_cast<ssize_t>(sizeof v);
    ::_exit(ok ? 0 : 1);
  }
  ::close(fds[1]);
  double v[6];
  const ssize_t got = pid > 0 ? ::read(fds[0], v, sizeof v) : 0;
  ::close(fds[0]);
  int status = 0;
  if (pid > 0) ::waitpid(pid, &status, 0);
  if (got != static_cast<ssize_t>(sizeof v)) {
    m.what += " — stopped by an assertion inside FCL";
    m.aborted = true;
    return m;
  }
  m.seconds = v[0];
  m.found = int(v[1]);
  m.missed = int(v[2]);
  m.false_contacts = int(v[3]);
  m.late_mm = v[4];
  m.early_mm = v[5];
  return m;
}

}  // namespace

int fcl_holder_table(int n, std::FILE* out) {
  const std::vector<Case> all = cases(n);
  std::vector<double> truth;
  int contacts = 0;
  for (const Case& c : all) {
    truth.push_back(true_first_contact(c));
    contacts += truth.back() >= 0;
  }
  std::vector<Method> rows;
  {  // qmotion: the certified interval must hold the true first contact.
    Method m{"qmotion `verify` (certified interval)"};
    const auto body = cam::holder_cores(kR, kH, kL);
    const cam::Stock stock{kStock, nullptr};
    int outside = 0;
    const auto t0 = std::chrono::steady_clock::now();
    for (std::size_t i = 0; i < all.size(); ++i) {
      cam::Move mv;
      mv.kind = cam::Move::Kind::traverse;
      mv.from = all[i].from;
      mv.to = all[i].to;
      const cam::Contact k = cam::first_contact(mv, 0, body, stock, nullptr, kTol);
      if (k.kind == cam::Contact::Kind::undecided) {
        ++m.undecided;
        continue;
      }
      const bool hit = k.kind == cam::Contact::Kind::contact;
      tally(m, truth[i], hit, k.t_hi, (mv.to - mv.from).norm());
      if (hit && truth[i] >= 0 && (truth[i] < k.t_lo || truth[i] > k.t_hi)) ++outside;
    }
    m.seconds = seconds_since(t0);
    if (outside) m.what += " — " + std::to_string(outside) + " intervals miss the truth";
    rows.push_back(m);
  }
  struct Mode {
    const char* what;
    fcl::CCDSolverType solver;
    fcl::CCDMotionType motion;
    std::size_t iterations;
    fcl::GJKSolverType gjk;
  };
  const auto CA = fcl::CCDC_CONSERVATIVE_ADVANCEMENT;
  const Mode modes[] = {
      {"FCL naive, 10 samples (its default)", fcl::CCDC_NAIVE, fcl::CCDM_TRANS, 10,
       fcl::GST_LIBCCD},
      {"FCL naive, 1000 samples", fcl::CCDC_NAIVE, fcl::CCDM_TRANS, 1000, fcl::GST_LIBCCD},
      {"FCL conservative advancement, translation, libccd", CA, fcl::CCDM_TRANS, 10,
       fcl::GST_LIBCCD},
      {"FCL conservative advancement, translation, FCL's GJK", CA, fcl::CCDM_TRANS, 10,
       fcl::GST_INDEP},
      {"FCL conservative advancement, linear interpolation, libccd", CA, fcl::CCDM_LINEAR, 10,
       fcl::GST_LIBCCD},
      {"FCL conservative advancement, linear interpolation, FCL's GJK", CA, fcl::CCDM_LINEAR, 10,
       fcl::GST_INDEP},
      {"FCL conservative advancement, screw motion, libccd", CA, fcl::CCDM_SCREW, 10,
       fcl::GST_LIBCCD},
      {"FCL conservative advancement, screw motion, FCL's GJK", CA, fcl::CCDM_SCREW, 10,
       fcl::GST_INDEP},
      {"FCL conservative advancement, spline motion, libccd", CA, fcl::CCDM_SPLINE, 10,
       fcl::GST_LIBCCD},
      {"FCL conservative advancement, spline motion, FCL's GJK", CA, fcl::CCDM_SPLINE, 10,
       fcl::GST_INDEP},
  };
  for (const Mode& mode : modes) {
    const Method m = run_fcl(mode.what, all, truth, [&](fcl::ContinuousCollisionRequestd& r) {
      r = fcl::ContinuousCollisionRequestd(mode.iterations, 1e-6, mode.motion, mode.gjk,
                                           mode.solver);
    });
    rows.push_back(m);
  }
  std::fprintf(out,
               "\nA holder (r %g, h %g, from %g mm up) along %d straight moves past a box of "
               "stock, entering it by 0.5 to 0.005 mm or clearing it by 0.005 to 0.5 mm (%d "
               "contacts, %d clear), T = %g mm:\n\n",
               kR, kH, kL, n, contacts, n - contacts, kTol);
  std::fprintf(out,
               "| method | time (s) | contacts found | missed | false contacts | undecided | "
               "first contact reported late by (mm along the move) | early by (mm) | time / "
               "qmotion's |\n| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
  for (const Method& m : rows)
    if (m.aborted)
      std::fprintf(out, "| %s | | | | | | | | |\n", m.what.c_str());
    else
      std::fprintf(out, "| %s | %.4f | %d | %d | %d | %d | %.3g | %.3g | %.2f |\n", m.what.c_str(),
                   m.seconds, m.found, m.missed, m.false_contacts, m.undecided, m.late_mm,
                   m.early_mm, m.seconds / rows.front().seconds);
  return rows.front().missed + rows.front().false_contacts +
         (rows.front().what.find("miss the truth") != std::string::npos);
}

}  // namespace qmotion::peers
