// <qmotion/render/canvas.hpp>: a 2-D vector figure (polylines, polygons, circles, text in pixel
// coordinates, y down) written as SVG or rasterised to PNG through cairo. The renderer and
// the plots draw on it; one drawing gives both formats.
#pragma once
#include <Eigen/Core>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace qmotion::render {

struct Rgb {
  double r = 0, g = 0, b = 0;  ///< each in [0, 1]
  std::string hex() const;     ///< "#rrggbb"
  /// Relative luminance (ITU-R BT.709): what a greyscale print keeps of the colour.
  double luminance() const { return 0.2126 * r + 0.7152 * g + 0.0722 * b; }
};

struct Style {
  std::optional<Rgb> stroke;  ///< none when absent
  std::optional<Rgb> fill;    ///< none when absent
  double width = 1;           ///< stroke width in pixels
  std::vector<double> dash;   ///< dash pattern in pixels (empty: solid)
  double opacity = 1;         ///< of the fill
  std::string cls;            ///< SVG class attribute (how a reader counts what is drawn)
};

enum class Anchor { start, middle, end };

class Canvas {
 public:
  /// A width x height pixel figure on `background`; Errc::invalid_input unless both sizes
  /// lie in [16, 20000].
  Canvas(int width, int height, Rgb background = {1, 1, 1});

  int width() const { return width_; }
  int height() const { return height_; }

  /// Groups the shapes drawn until end_group() (an SVG <g class="...">, nestable).
  void begin_group(const std::string& cls);
  void end_group();
  void polyline(std::vector<Eigen::Vector2d> points, const Style& style);
  void polygon(std::vector<Eigen::Vector2d> points, const Style& style);
  void circle(const Eigen::Vector2d& centre, double radius, const Style& style);
  void text(const Eigen::Vector2d& at, const std::string& s, double size, Anchor anchor,
            Rgb colour = {}, bool bold = false);
  /// A data-KEY="VALUE" attribute of the SVG root (how a reader finds the projection).
  void attribute(const std::string& key, const std::string& value);

  /// The width of `s` in a sans-serif font of `size` pixels, estimated (0.6 em a glyph): an
  /// upper bound for Latin text, used to fit titles and labels.
  static double text_width(const std::string& s, double size);

  std::string svg() const;
  /// Writes the figure by the extension of `path`: .svg, or .png rasterised by cairo;
  /// atomically (nothing is left behind on failure). Errc::invalid_input for another
  /// extension or an unwritable path.
  void write(const std::string& path) const;

 private:
  enum class Kind { polyline, polygon, circle, text, group_begin, group_end };
  struct Shape {
    Kind kind = Kind::polyline;
    std::vector<Eigen::Vector2d> points;
    Style style;
    double size = 0;  ///< circle radius or font size
    std::string text;
    Anchor anchor = Anchor::start;
    bool bold = false;
  };
  void add_path(Kind kind, std::vector<Eigen::Vector2d> points, const Style& style);
  void write_png(const std::string& path) const;

  int width_, height_;
  Rgb background_;
  std::vector<Shape> shapes_;
  std::vector<std::pair<std::string, std::string>> attributes_;
  int open_groups_ = 0;
};

/// Errc::invalid_input unless `path` ends in .svg or .png (any case): what Canvas::write
/// accepts, checked by the callers before any work.
void check_figure_path(const std::string& path);

}  // namespace qmotion::render
