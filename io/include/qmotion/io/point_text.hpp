// <qmotion/io/point_text.hpp>: numbers given as text on a command line ("x,y,z", a profile's
// or a body's sizes).
#pragma once
#include <Eigen/Core>
#include <qmotion/io/json_number.hpp>
#include <qmotion/kernel/error.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace qmotion::io {

/// The comma-separated numbers of text, each as parse_number_text reads it (naming `where`
/// when one is not a number); as many as there are.
inline std::vector<double> parse_numbers(const std::string& text, const std::string& where) {
  std::vector<double> v;
  std::stringstream ss(text);
  std::string cell;
  while (std::getline(ss, cell, ',')) v.push_back(parse_number_text(cell, where).value);
  return v;
}

/// Parses "x,y,z" given to `flag` (each number as parse_number_text reads it);
/// Errc::invalid_input naming the flag unless there are exactly three.
inline Eigen::Vector3d parse_point(const std::string& text, const std::string& flag) {
  const std::vector<double> v = parse_numbers(text, flag);
  if (v.size() != 3)
    throw Error(Errc::invalid_input, flag + ": expected three numbers x,y,z, found '" + text + "'");
  return Eigen::Vector3d(v[0], v[1], v[2]);
}

}  // namespace qmotion::io
