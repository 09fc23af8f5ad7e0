// python/pictures.cpp: render and plot.
#include "convert.hpp"

namespace qmotion::python {
namespace {

/// `qmotion render` as a call; the dict of what was drawn.
py::object render_call(const PyMotion& motion, const std::string& path, const py::object& points,
                       const py::object& profile, const std::string& view,
                       const std::pair<int, int>& size, int frames, const std::string& object,
                       double object_size, const std::string& title) {
  const Motion& m = motion.motion;
  render::RenderOptions o;
  o.output = path;
  if (!points.is_none())
    for (const auto& p : points) o.points.push_back(vec3(p, "points"));
  if (!profile.is_none()) o.profile = to_profile(profile, m.units());
  o.view = view;
  std::tie(o.width, o.height) = size;
  o.frames = frames;
  o.object = object;
  o.object_size = object_size;
  o.title = title;
  const auto r = render::render(m, o);
  py::dict d;
  d["path"] = r.path;
  d["width"] = r.width;
  d["height"] = r.height;
  d["trajectories"] = r.trajectories;
  d["object_poses"] = r.object_poses;
  d["key_poses"] = r.key_poses;
  d["key_markers"] = r.key_markers;
  d["surface_quads"] = r.surface_quads;
  d["scale"] = r.scale;
  d["origin"] = std::vector<double>{r.origin.x(), r.origin.y()};
  d["object_size"] = r.object_size;
  return std::move(d);
}

}  // namespace

void bind_pictures(py::module_& m) {
  m.def("render", &render_call, py::arg("motion"), py::arg("path"), py::arg("points") = py::none(),
        py::arg("profile") = py::none(), py::arg("view") = "iso",
        py::arg("size") = std::pair<int, int>(960, 720), py::arg("frames") = 7,
        py::arg("object") = "cube", py::arg("object_size") = 0.0, py::arg("title") = "",
        "`qmotion render`: the motion drawn to path (.svg or .png): the "
        "object at frames evenly spaced times, the numbered key poses, the trajectories of "
        "points (default the origin), the swept surface of profile, axes and a scale bar, in "
        "the orthographic view (iso, top, front, side or a direction 'x,y,z'). Returns a dict "
        "of what was drawn and the projection (scale in pixels per unit, origin in pixels).");
  m.def(
      "plot",
      [](const py::object& motions, const std::string& path, const std::string& quantity,
         const py::object& point, const std::pair<int, int>& size, int samples,
         const std::string& title) {
        std::vector<Motion> ms;
        if (py::isinstance<py::list>(motions) || py::isinstance<py::tuple>(motions)) {
          for (const auto& m : motions) ms.push_back(m.cast<const PyMotion&>().motion);
        } else {
          ms.push_back(motions.cast<const PyMotion&>().motion);
        }
        render::PlotOptions o;
        o.output = path;
        o.quantity = render::parse_quantity(quantity);
        if (!point.is_none()) o.point = vec3(point, "point");
        std::tie(o.width, o.height) = size;
        o.samples = samples;
        o.title = title;
        py::list out;
        for (const auto& s : render::plot(ms, o)) {
          py::dict d;
          d["name"] = s.name;
          d["t"] = py::array_t<double>(static_cast<py::ssize_t>(s.t.size()), s.t.data());
          d["value"] =
              py::array_t<double>(static_cast<py::ssize_t>(s.value.size()), s.value.data());
          d["keys"] = s.keys;
          d["min"] = s.min;
          d["max"] = s.max;
          d["t_min"] = s.t_min;
          d["t_max"] = s.t_max;
          out.append(d);
        }
        return out;
      },
      py::arg("motions"), py::arg("path"), py::arg("quantity") = "speed",
      py::arg("point") = py::none(), py::arg("size") = std::pair<int, int>(900, 500),
      py::arg("samples") = 600, py::arg("title") = "",
      "`qmotion plot`: speed, angular-speed, curvature or weights along t for one motion or a "
      "list of them (compared on one plot), written to path (.svg or .png). Returns one dict "
      "per motion: name, t and value (numpy), keys, min, max, t_min, t_max.");
}

}  // namespace qmotion::python
