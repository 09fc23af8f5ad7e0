// render/src/canvas.cpp
#include <cairo.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <qmotion/io/atomic_file.hpp>
#include <qmotion/kernel/error.hpp>
#include <qmotion/render/canvas.hpp>

#include "drawing.hpp"

namespace qmotion::render {
using namespace io;  // NOLINT: the formats this call reads and writes
using detail::escape_xml;

namespace {

/// Pixel coordinates in SVG: two decimals are a hundredth of a pixel.
std::string px(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", std::abs(v) < 0.005 ? 0.0 : v);
  return buf;
}

std::string style_attributes(const Style& s) {
  std::string a = s.cls.empty() ? std::string() : " class=\"" + escape_xml(s.cls) + "\"";
  a += " fill=\"" + (s.fill ? s.fill->hex() : std::string("none")) + "\"";
  if (s.fill && s.opacity < 1) a += " fill-opacity=\"" + px(s.opacity) + "\"";
  if (s.stroke) {
    a += " stroke=\"" + s.stroke->hex() + "\" stroke-width=\"" + px(s.width) +
         "\" stroke-linejoin=\"round\" stroke-linecap=\"round\"";
    if (!s.dash.empty()) {
      a += " stroke-dasharray=\"";
      for (std::size_t i = 0; i < s.dash.size(); ++i) a += (i ? "," : "") + px(s.dash[i]);
      a += "\"";
    }
  }
  return a;
}

}  // namespace

std::string detail::escape_xml(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string Rgb::hex() const {
  auto byte = [](double v) {
    return static_cast<unsigned>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0));
  };
  char buf[8];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", byte(r), byte(g), byte(b));
  return buf;
}

void check_figure_path(const std::string& path) {
  const std::string e = lower_extension(path);
  if (e != ".svg" && e != ".png")
    throw Error(Errc::invalid_input,
                "-o " + path + ": expected a figure file ending in .svg or .png");
}

Canvas::Canvas(int width, int height, Rgb background)
    : width_(width), height_(height), background_(background) {
  if (width < 16 || height < 16 || width > 20000 || height > 20000)
    throw Error(Errc::invalid_input, "--size " + std::to_string(width) + "," +
                                         std::to_string(height) +
                                         ": expected a width and height of 16 to 20000 pixels");
}

void Canvas::begin_group(const std::string& cls) {
  Shape s;
  s.kind = Kind::group_begin;
  s.text = cls;
  shapes_.push_back(std::move(s));
  ++open_groups_;
}

void Canvas::end_group() {
  if (open_groups_ == 0) return;
  Shape s;
  s.kind = Kind::group_end;
  shapes_.push_back(std::move(s));
  --open_groups_;
}

void Canvas::add_path(Kind kind, std::vector<Eigen::Vector2d> points, const Style& style) {
  if (points.size() < (kind == Kind::polygon ? 3u : 2u)) return;  // nothing to draw
  Shape s;
  s.kind = kind;
  s.points = std::move(points);
  s.style = style;
  shapes_.push_back(std::move(s));
}

void Canvas::polyline(std::vector<Eigen::Vector2d> points, const Style& style) {
  add_path(Kind::polyline, std::move(points), style);
}

void Canvas::polygon(std::vector<Eigen::Vector2d> points, const Style& style) {
  add_path(Kind::polygon, std::move(points), style);
}

void Canvas::circle(const Eigen::Vector2d& centre, double radius, const Style& style) {
  Shape s;
  s.kind = Kind::circle;
  s.points = {centre};
  s.size = radius;
  s.style = style;
  shapes_.push_back(std::move(s));
}

void Canvas::text(const Eigen::Vector2d& at, const std::string& str, double size, Anchor anchor,
                  Rgb colour, bool bold) {
  Shape s;
  s.kind = Kind::text;
  s.points = {at};
  s.text = str;
  s.size = size;
  s.anchor = anchor;
  s.style.fill = colour;
  s.bold = bold;
  shapes_.push_back(std::move(s));
}

void Canvas::attribute(const std::string& key, const std::string& value) {
  attributes_.emplace_back(key, value);
}

double Canvas::text_width(const std::string& s, double size) {
  std::size_t glyphs = 0;  // UTF-8: count the bytes that start a character
  for (unsigned char c : s) glyphs += (c & 0xC0) != 0x80;
  return 0.6 * size * static_cast<double>(glyphs);
}

std::string Canvas::svg() const {
  std::string o;
  o.reserve(256 + shapes_.size() * 96);
  o += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" "
       "width=\"" +
       std::to_string(width_) + "\" height=\"" + std::to_string(height_) + "\" viewBox=\"0 0 " +
       std::to_string(width_) + " " + std::to_string(height_) + "\"";
  for (const auto& [k, v] : attributes_) o += " data-" + k + "=\"" + escape_xml(v) + "\"";
  o += ">\n<rect width=\"100%\" height=\"100%\" fill=\"" + background_.hex() + "\"/>\n";
  int depth = 0;
  for (const Shape& s : shapes_) {
    switch (s.kind) {
      case Kind::group_begin:
        o += "<g class=\"" + escape_xml(s.text) + "\">\n";
        ++depth;
        break;
      case Kind::group_end:
        o += "</g>\n";
        --depth;
        break;
      case Kind::polyline:
      case Kind::polygon: {
        o += s.kind == Kind::polyline ? "<polyline points=\"" : "<polygon points=\"";
        for (std::size_t i = 0; i < s.points.size(); ++i) {
          if (i) o += ' ';
          o += px(s.points[i].x()) + "," + px(s.points[i].y());
        }
        o += "\"" + style_attributes(s.style) + "/>\n";
        break;
      }
      case Kind::circle:
        o += "<circle cx=\"" + px(s.points[0].x()) + "\" cy=\"" + px(s.points[0].y()) + "\" r=\"" +
             px(s.size) + "\"" + style_attributes(s.style) + "/>\n";
        break;
      case Kind::text: {
        const char* anchor = s.anchor == Anchor::start    ? "start"
                             : s.anchor == Anchor::middle ? "middle"
                                                          : "end";
        o += "<text x=\"" + px(s.points[0].x()) + "\" y=\"" + px(s.points[0].y()) +
             "\" font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\" font-size=\"" +
             px(s.size) + "\" text-anchor=\"" + anchor + "\" fill=\"" + s.style.fill->hex() + "\"" +
             (s.bold ? " font-weight=\"bold\"" : "") + ">" + escape_xml(s.text) + "</text>\n";
        break;
      }
    }
  }
  for (; depth > 0; --depth) o += "</g>\n";
  o += "</svg>\n";
  return o;
}

void Canvas::write(const std::string& path) const {
  check_figure_path(path);
  if (lower_extension(path) == ".svg")
    write_file_atomic(path, svg());
  else
    write_png(path);
}

void Canvas::write_png(const std::string& path) const {
  struct Surface {
    cairo_surface_t* s;
    cairo_t* c;
    ~Surface() {
      cairo_destroy(c);
      cairo_surface_destroy(s);
    }
  } d{cairo_image_surface_create(CAIRO_FORMAT_RGB24, width_, height_), nullptr};
  d.c = cairo_create(d.s);
  cairo_t* c = d.c;
  if (cairo_status(c) != CAIRO_STATUS_SUCCESS)
    throw Error(Errc::invalid_input, "-o " + path + ": cannot create a " + std::to_string(width_) +
                                         "x" + std::to_string(height_) + " image (" +
                                         cairo_status_to_string(cairo_status(c)) + ")");
  cairo_set_source_rgb(c, background_.r, background_.g, background_.b);
  cairo_paint(c);
  cairo_set_line_join(c, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_cap(c, CAIRO_LINE_CAP_ROUND);
  auto paint = [c](const Style& st) {
    if (st.fill) {
      cairo_set_source_rgba(c, st.fill->r, st.fill->g, st.fill->b, st.opacity);
      if (st.stroke)
        cairo_fill_preserve(c);
      else
        cairo_fill(c);
    }
    if (st.stroke) {
      cairo_set_source_rgb(c, st.stroke->r, st.stroke->g, st.stroke->b);
      cairo_set_line_width(c, st.width);
      cairo_set_dash(c, st.dash.empty() ? nullptr : st.dash.data(),
                     static_cast<int>(st.dash.size()), 0);
      cairo_stroke(c);
    }
    cairo_new_path(c);
  };
  for (const Shape& s : shapes_) {
    switch (s.kind) {
      case Kind::group_begin:
      case Kind::group_end:
        break;
      case Kind::polyline:
      case Kind::polygon:
        cairo_move_to(c, s.points[0].x(), s.points[0].y());
        for (std::size_t i = 1; i < s.points.size(); ++i)
          cairo_line_to(c, s.points[i].x(), s.points[i].y());
        if (s.kind == Kind::polygon) cairo_close_path(c);
        paint(s.style);
        break;
      case Kind::circle:
        cairo_new_sub_path(c);
        cairo_arc(c, s.points[0].x(), s.points[0].y(), s.size, 0, 2 * M_PI);
        paint(s.style);
        break;
      case Kind::text: {
        cairo_select_font_face(c, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL,
                               s.bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
        cairo_set_font_size(c, s.size);
        cairo_text_extents_t ext;
        cairo_text_extents(c, s.text.c_str(), &ext);
        const double shift = s.anchor == Anchor::start    ? 0
                             : s.anchor == Anchor::middle ? ext.x_advance / 2
                                                          : ext.x_advance;
        cairo_move_to(c, s.points[0].x() - shift, s.points[0].y());
        cairo_set_source_rgb(c, s.style.fill->r, s.style.fill->g, s.style.fill->b);
        cairo_show_text(c, s.text.c_str());
        cairo_new_path(c);
        break;
      }
    }
  }
  cairo_surface_flush(d.s);
  AtomicOutput out(path);
  const cairo_status_t st = cairo_surface_write_to_png(d.s, out.temp_path().c_str());
  if (st != CAIRO_STATUS_SUCCESS)
    throw Error(Errc::invalid_input,
                "-o " + path + ": cannot write the PNG (" + cairo_status_to_string(st) + ")");
  out.commit();
}

}  // namespace qmotion::render
