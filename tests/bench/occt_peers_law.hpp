// tests/bench/occt_peers_law.hpp: route 2 of tests/bench/occt_peers.cpp, GeomFill_Sweep's
// location law written from our motion's exact frame (what an OpenCASCADE user writes to
// sweep along a rigid motion they can evaluate).
#pragma once
#include <memory>
#include <vector>

#include "occt_peers_case.hpp"
// clang-format off
#include <GeomFill_LocationLaw.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <gp_Mat.hxx>
#include <gp_Vec.hxx>
// clang-format on

namespace qmotion::bench {

inline gp_Mat to_gp_mat(const Eigen::Matrix3d& m) {
  return gp_Mat(m(0, 0), m(0, 1), m(0, 2), m(1, 0), m(1, 1), m(1, 2), m(2, 0), m(2, 1), m(2, 2));
}
inline gp_Vec to_gp_vec(const V3& v) { return gp_Vec(v.x(), v.y(), v.z()); }

/// The section is placed at M * P + V with M = R(t) and V = T(t) of our motion: the
/// location law an OpenCASCADE user writes to sweep along a rigid motion they can evaluate.
class MotionLaw : public GeomFill_LocationLaw {
 public:
  explicit MotionLaw(std::shared_ptr<const Frames> f)
      : f_(std::move(f)), first_(f_->a), last_(f_->b) {}

  void SetCurve(const Handle(Adaptor3d_Curve) &) override {}
  const Handle(Adaptor3d_Curve) & GetCurve() const override { return curve_; }
  void SetTrsf(const gp_Mat& t) override { trsf_ = t; }
  Handle(GeomFill_LocationLaw) Copy() const override {
    Handle(MotionLaw) c = new MotionLaw(f_);
    c->trsf_ = trsf_;
    c->first_ = first_;
    c->last_ = last_;
    return c;
  }
  Standard_Boolean D0(const Standard_Real t, gp_Mat& M, gp_Vec& V) override {
    M4 H;
    f_->at(t, H);
    M = to_gp_mat(H.block<3, 3>(1, 1)) * trsf_;
    V = to_gp_vec(H.block<3, 1>(1, 0));
    return Standard_True;
  }
  Standard_Boolean D0(const Standard_Real t, gp_Mat& M, gp_Vec& V, TColgp_Array1OfPnt2d&) override {
    return D0(t, M, V);
  }
  Standard_Boolean D1(const Standard_Real t, gp_Mat& M, gp_Vec& V, gp_Mat& DM, gp_Vec& DV,
                      TColgp_Array1OfPnt2d&, TColgp_Array1OfVec2d&) override {
    M4 H, dH;
    f_->at(t, H, &dH);
    M = to_gp_mat(H.block<3, 3>(1, 1)) * trsf_;
    V = to_gp_vec(H.block<3, 1>(1, 0));
    DM = to_gp_mat(dH.block<3, 3>(1, 1)) * trsf_;
    DV = to_gp_vec(dH.block<3, 1>(1, 0));
    return Standard_True;
  }
  Standard_Boolean D2(const Standard_Real t, gp_Mat& M, gp_Vec& V, gp_Mat& DM, gp_Vec& DV,
                      gp_Mat& D2M, gp_Vec& D2V, TColgp_Array1OfPnt2d&, TColgp_Array1OfVec2d&,
                      TColgp_Array1OfVec2d&) override {
    M4 H, dH, ddH;
    f_->at(t, H, &dH, &ddH);
    M = to_gp_mat(H.block<3, 3>(1, 1)) * trsf_;
    V = to_gp_vec(H.block<3, 1>(1, 0));
    DM = to_gp_mat(dH.block<3, 3>(1, 1)) * trsf_;
    DV = to_gp_vec(dH.block<3, 1>(1, 0));
    D2M = to_gp_mat(ddH.block<3, 3>(1, 1)) * trsf_;
    D2V = to_gp_vec(ddH.block<3, 1>(1, 0));
    return Standard_True;
  }
  Standard_Integer NbIntervals(const GeomAbs_Shape S) const override {
    return static_cast<Standard_Integer>(inside(S).size()) + 1;
  }
  void Intervals(TColStd_Array1OfReal& T, const GeomAbs_Shape S) const override {
    const auto b = inside(S);
    T.SetValue(T.Lower(), first_);
    for (std::size_t i = 0; i < b.size(); ++i)
      T.SetValue(T.Lower() + static_cast<int>(i) + 1, b[i]);
    T.SetValue(T.Upper(), last_);
  }
  void SetInterval(const Standard_Real a, const Standard_Real b) override {
    first_ = a;
    last_ = b;
  }
  void GetInterval(Standard_Real& a, Standard_Real& b) const override {
    a = first_;
    b = last_;
  }
  void GetDomain(Standard_Real& a, Standard_Real& b) const override {
    a = f_->a;
    b = f_->b;
  }
  Standard_Real GetMaximalNorm() override {
    double n = 0;
    for (int i = 0; i <= 200; ++i) {
      M4 H;
      f_->at(f_->a + (f_->b - f_->a) * i / 200.0, H);
      n = std::max(n, H.block<3, 1>(1, 0).norm());
    }
    return n;
  }
  void GetAverageLaw(gp_Mat& AM, gp_Vec& AV) override {
    M4 sum = M4::Zero();
    for (int i = 0; i <= 100; ++i) {
      M4 H;
      f_->at(f_->a + (f_->b - f_->a) * i / 100.0, H);
      sum += H / 101.0;
    }
    AM = to_gp_mat(sum.block<3, 3>(1, 1));
    AV = to_gp_vec(sum.block<3, 1>(1, 0));
  }

 private:
  std::vector<double> inside(GeomAbs_Shape S) const {
    const int k = S == GeomAbs_C0 ? 0 : S == GeomAbs_C1 ? 1 : S == GeomAbs_C2 ? 2 : 3;
    std::vector<double> out;
    for (double x : f_->breaks(k))
      if (x > first_ && x < last_) out.push_back(x);
    return out;
  }
  std::shared_ptr<const Frames> f_;
  Handle(Adaptor3d_Curve) curve_;
  gp_Mat trsf_{1, 0, 0, 0, 1, 0, 0, 0, 1};
  double first_, last_;
};

}  // namespace qmotion::bench
