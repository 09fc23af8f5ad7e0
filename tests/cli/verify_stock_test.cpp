// tests/cli/verify_stock_test.cpp: `qmotion verify --stock --map`: the stock left by a ball
// cutter at a known stepover against the scallop's height and against the distance
// integrated here, and the map's colours where the program gouges, cuts and leaves stock.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "cli_util.hpp"

namespace qmotion::test {
namespace {

/// A closed box mesh [lo, hi] whose six faces are grids of n x n squares, as OBJ.
fs::path grid_box(const std::array<double, 3>& lo, const std::array<double, 3>& hi, int n,
                  const std::string& name) {
  std::map<std::array<int, 3>, int> index;
  std::vector<std::array<int, 3>> vertices;
  auto id = [&](std::array<int, 3> p) {
    const auto [it, fresh] = index.emplace(p, static_cast<int>(vertices.size()));
    if (fresh) vertices.push_back(p);
    return it->second + 1;
  };
  std::ostringstream faces;
  for (int k = 0; k < 3; ++k)
    for (int side = 0; side < 2; ++side) {
      const int u = (k + 1) % 3, v = (k + 2) % 3;
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          std::array<std::array<int, 3>, 4> q;
          const int di[4] = {0, 1, 1, 0}, dj[4] = {0, 0, 1, 1};
          for (int c = 0; c < 4; ++c) {
            q[static_cast<std::size_t>(c)][static_cast<std::size_t>(k)] = side * n;
            q[static_cast<std::size_t>(c)][static_cast<std::size_t>(u)] = i + di[c];
            q[static_cast<std::size_t>(c)][static_cast<std::size_t>(v)] = j + dj[c];
          }
          // u x v is +k: counter-clockwise seen from outside on the far side.
          const int a = id(q[0]), b = id(q[1]), c = id(q[2]), d = id(q[3]);
          if (side == 1)
            faces << "f " << a << " " << b << " " << c << "\nf " << a << " " << c << " " << d
                  << "\n";
          else
            faces << "f " << a << " " << c << " " << b << "\nf " << a << " " << d << " " << c
                  << "\n";
        }
    }
  const fs::path p = scratch_dir() / name;
  std::ofstream f(p);
  f.precision(17);
  for (const auto& q : vertices) {
    f << "v";
    for (std::size_t k = 0; k < 3; ++k) f << " " << lo[k] + (hi[k] - lo[k]) * q[k] / n;
    f << "\n";
  }
  f << faces.str();
  return p;
}

/// Passes along x from -14 to 14 at y = y0, y0 + 1, ... y1, the tip at z; then `extra`.
fs::path raster(const std::string& name, int y0, int y1, double z, const std::string& extra) {
  const fs::path p = scratch_dir() / name;
  std::ofstream f(p);
  f << "G21 G90 G17\nG0 Z10\nG0 X-14 Y" << y0 << "\nG1 Z" << z << " F1000\n";
  int x = -14;
  for (int y = y0; y <= y1; ++y) {
    if (y > y0) f << "G1 Y" << y << "\n";
    x = -x;
    f << "G1 X" << x << "\n";
  }
  f << "G0 Z10\n" << extra << "M2\n";
  return p;
}

json verify_stock(const fs::path& program, const fs::path& part, const std::string& map,
                  const std::string& stock = "box:-10,-10,-5,10,10,1") {
  std::vector<std::string> args = {
      "verify", program.string(), "--tool", "cutter:ball,6,20", "--part", part.string(), "--stock",
      stock,    "--tol",          "0.01"};
  if (!map.empty()) args.insert(args.end(), {"--map", map});
  return run_json(args);
}

/// A ball of radius r = 3 at stepover s = 1 over a flat part: the largest stock left is at
/// the ridges between passes. Its distance to the cutter, sqrt(r^2 + s^2/4) - r, lies in
/// the certified interval, which is within T of the scallop's height r - sqrt(r^2 - s^2/4).
TEST(VerifyStock, ScallopOfABallCutterAtAKnownStepover) {
  const fs::path part = grid_box({-10, -10, -5}, {10, 10, 0}, 20, "grid_plate.obj");
  // The stock over the middle 10 x 10 mm of the part's top, 1 mm thick.
  const json r =
      verify_stock(raster("scallop.ngc", -13, 13, 0, ""), part, "", "box:-5,-5,-5,5,5,1");
  const json& s = r["stock_left"];
  const double R = 3, a = 0.5, tol = 0.01;
  const double distance = std::sqrt(R * R + a * a) - R, height = R - std::sqrt(R * R - a * a);
  const double lo = s["max"][0], hi = s["max"][1];
  EXPECT_TRUE(s["max_certified"].get<bool>());
  EXPECT_LE(hi - lo, tol);
  EXPECT_LE(lo, distance + 1e-12);
  EXPECT_GE(hi, distance - 1e-12);
  EXPECT_LE(std::abs(lo - height), tol);
  EXPECT_LE(std::abs(hi - height), tol);
  // Reached on a ridge (y half-way between passes), on the part's top, by a pass.
  const json& w = s["where"];
  const double y = w["point"][1];
  EXPECT_LE(std::abs(std::abs(y - std::round(y)) - 0.5), 0.1) << w.dump();
  EXPECT_NEAR(w["point"][2].get<double>(), 0, 1e-9);
  EXPECT_EQ(w["nearest"], "cutter");
  // The mean over the top's middle (the only part of the surface inside the stock),
  // integrated here by the midpoint rule: min(depth in the stock, distance to the passes).
  double sum = 0;
  const int n = 2000;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double px = -5 + 10 * (i + 0.5) / n, py = -5 + 10 * (j + 0.5) / n;
      const double f = std::abs(py - std::round(py));
      const double depth = std::min({px + 5, 5 - px, py + 5, 5 - py, 1.0});
      sum += std::min(depth, std::sqrt(R * R + f * f) - R);
    }
  const double mean = sum / (double(n) * n);
  EXPECT_LE(s["mean"][0].get<double>(), mean + 1e-6);
  EXPECT_GE(s["mean"][1].get<double>(), mean - 1e-6);
  EXPECT_NEAR(s["mean_estimate"].get<double>(), mean, tol / 2);
  EXPECT_NEAR(s["area_in_stock"].get<double>(), 100, 1);
}

/// Without a stock there are no stock figures.
TEST(VerifyStock, NoStockNoFigures) {
  const json r = run_json({"verify", raster("plain.ngc", -2, 2, 0, "").string(), "--tool",
                           "cutter:ball,6,20", "--part", test_data("verify/plate.obj")});
  EXPECT_FALSE(r.contains("stock_left"));
}

struct Ply {
  std::vector<std::array<double, 3>> xyz;
  std::vector<std::array<int, 3>> rgb;
};

/// Reads the map's binary PLY: double x, y, z and uchar red, green, blue per vertex.
Ply read_ply(const fs::path& p) {
  const std::string s = slurp(p);
  Ply ply;
  const auto end = s.find("end_header\n");
  EXPECT_NE(end, std::string::npos);
  const std::string header = s.substr(0, end);
  EXPECT_NE(header.find("property uchar red\nproperty uchar green\nproperty uchar blue"),
            std::string::npos);
  const auto at = header.find("element vertex ");
  const std::size_t count = std::stoul(header.substr(at + 15));
  std::size_t o = end + 11;
  for (std::size_t i = 0; i < count; ++i, o += 27) {
    std::array<double, 3> x;
    std::memcpy(x.data(), s.data() + o, 24);
    ply.xyz.push_back(x);
    ply.rgb.push_back({static_cast<unsigned char>(s[o + 24]), static_cast<unsigned char>(s[o + 25]),
                       static_cast<unsigned char>(s[o + 26])});
  }
  return ply;
}

/// Passes at z = 0 over y <= 0, and one 0.05 mm into the part at y = -5: red along the
/// gouge, grey (on size) under the passes, blue where the stock was never reached.
TEST(VerifyStock, MapColoursGougeOnSizeAndStock) {
  const fs::path part = grid_box({-10, -10, -5}, {10, 10, 0}, 20, "grid_plate.obj");
  const fs::path program =
      raster("gouge_map.ngc", -13, 0, 0, "G0 X-14 Y-5\nG1 Z-0.05\nG1 X14\nG0 Z10\n");
  const fs::path ply = scratch_dir() / "map.ply";
  const json r = verify_stock(program, part, ply.string());
  EXPECT_NEAR(r["gouge"]["depth"][0].get<double>(), 0.05, 0.01);
  const Ply m = read_ply(ply);
  ASSERT_EQ(m.xyz.size(), 6u * 20 * 20 + 2);  // the grid box's vertices
  int red = 0, grey = 0, blue = 0;
  for (std::size_t i = 0; i < m.xyz.size(); ++i) {
    const auto [x, y, z] = m.xyz[i];
    const auto [cr, cg, cb] = m.rgb[i];
    if (z != 0 || std::abs(x) > 9) continue;
    if (y == -5) {
      EXPECT_GT(cr, cg + 60) << x << " " << y;  // red
      ++red;
    } else if (y >= -9 && y <= -1) {
      EXPECT_EQ(cr, cg);  // grey: on size under a pass at z = 0
      EXPECT_EQ(cg, cb);
      ++grey;
    } else if (y >= 4 && y <= 9) {              // y = 10 lies on the stock's face: no stock
      EXPECT_GT(cb, cr + 60) << x << " " << y;  // blue: 1 mm of stock left
      ++blue;
    }
  }
  EXPECT_GT(red, 10);
  EXPECT_GT(grey, 50);
  EXPECT_GT(blue, 50);
  // The pictures: a view from above, one polygon per upward triangle (the top's 800).
  const fs::path svg = scratch_dir() / "map.svg", png = scratch_dir() / "map.png";
  verify_stock(program, part, svg.string());
  const std::string text = slurp(svg);
  EXPECT_NE(text.find("data-view=\"top\""), std::string::npos);
  std::size_t polygons = 0;
  for (auto at = text.find("<polygon"); at != std::string::npos; at = text.find("<polygon", at + 1))
    ++polygons;
  EXPECT_EQ(polygons, 800u + 6);  // and the scale's six swatches
  verify_stock(program, part, png.string());
  EXPECT_EQ(slurp(png).substr(0, 4), "\x89PNG");
}

}  // namespace
}  // namespace qmotion::test
