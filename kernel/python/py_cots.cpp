// Python bindings of the planar COTS map and the 3D BeCOTS map: thin conversions, no logic.
#include <pybind11/complex.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>

#include "convert.hpp"
#include "steady/cots/becots_lattice.hpp"
#include "steady/cots/becots_map.hpp"
#include "steady/cots/becots_range.hpp"
#include "steady/cots/becots_sums.hpp"
#include "steady/cots/cots_map.hpp"
#include "steady/query/becots_query.hpp"

namespace steadypy {

using steady::Ball;
using steady::BecotsMap;
using steady::BecotsRangeFinder;
using steady::CotsMap;
using steady::CotsPreimage;
using steady::Vec2;
using steady::Vec3;

namespace {

// Images of an N x 2 array of parameters (x, y) (or of one pair), as N x Dims (or Dims) coordinates.
template <int Dims, class Map>
py::array_t<double> map_parameters(const Map& map, py::handle uv) {
  bool single = false;
  auto in = to_points(uv, "uv", 2, &single);
  const py::ssize_t n = in.shape(0);
  py::array_t<double> out({n, py::ssize_t(Dims)});
  const double* src = in.data();
  double* dst = out.mutable_data();
  {
    py::gil_scoped_release release;
    for (py::ssize_t q = 0; q < n; ++q) {
      const auto p = map.map(src[2 * q], src[2 * q + 1]);
      for (int k = 0; k < Dims; ++k) dst[Dims * q + k] = p[k];
    }
  }
  if (single) return out.reshape({py::ssize_t(Dims)});
  return out;
}

py::object preimage_array(const std::vector<CotsPreimage>& found, bool with_branches) {
  py::array_t<double> uv({py::ssize_t(found.size()), py::ssize_t(2)});
  py::array_t<int> branches(py::ssize_t(found.size()));
  auto u = uv.mutable_unchecked<2>();
  auto b = branches.mutable_unchecked<1>();
  for (std::size_t k = 0; k < found.size(); ++k) {
    u(k, 0) = found[k].uv.x, u(k, 1) = found[k].uv.y;
    b(k) = found[k].branch;
  }
  if (with_branches) return py::make_tuple(uv, branches);
  return std::move(uv);
}

// Pre-images of one point (dims coordinates: a K x 2 array) or of N points (a list of N such arrays).
template <int Dims, class Invert>
py::object preimages(py::handle points, bool with_branches, Invert invert) {
  bool single = false;
  auto in = to_points(points, "points", Dims, &single);
  const py::ssize_t n = in.shape(0);
  std::vector<std::vector<CotsPreimage>> found(n);
  const double* src = in.data();
  {
    py::gil_scoped_release release;
    for (py::ssize_t q = 0; q < n; ++q) found[q] = invert(src + Dims * q);
  }
  if (single) return preimage_array(found[0], with_branches);
  py::list out;
  for (const auto& f : found) out.append(preimage_array(f, with_branches));
  return std::move(out);
}

template <int Dims, class Tiles>
py::object tiles(py::handle points, Tiles tiles_of) {
  bool single = false;
  auto in = to_points(points, "points", Dims, &single);
  py::list out;
  for (py::ssize_t q = 0; q < in.shape(0); ++q) {
    py::list t;
    for (const auto& ij : tiles_of(in.data() + Dims * q)) t.append(py::make_tuple(ij[0], ij[1]));
    if (single) return std::move(t);
    out.append(t);
  }
  return std::move(out);
}

steady::ParameterBox to_box(py::handle box) {
  if (box.is_none()) return {};
  auto s = py::reinterpret_borrow<py::sequence>(box);
  if (!py::isinstance<py::sequence>(box) || s.size() != 4) value_error("box", "expected (x0, x1, y0, y1) or None");
  return {to_double(s[0], "box[0]"), to_double(s[1], "box[1]"), to_double(s[2], "box[2]"), to_double(s[3], "box[3]")};
}

std::pair<int, int> to_branches(py::handle value) {
  auto s = py::reinterpret_borrow<py::sequence>(value);
  if (!py::isinstance<py::sequence>(value) || s.size() != 2) value_error("branches", "expected (branch_u, branch_v)");
  const auto bu = to_int(s[0], "branches[0]"), bv = to_int(s[1], "branches[1]");
  if (bu < -steady::kCotsMaxBranch || bu > steady::kCotsMaxBranch || bv < -steady::kCotsMaxBranch ||
      bv > steady::kCotsMaxBranch)
    value_error("branches", "each must be within +-" + std::to_string(steady::kCotsMaxBranch) + " turns");
  return {static_cast<int>(bu), static_cast<int>(bv)};
}

py::array_t<double> vec2_array(const Vec2& v) {
  py::array_t<double> a(2);
  a.mutable_at(0) = v.x;
  a.mutable_at(1) = v.y;
  return a;
}

template <class V, int Dims>
py::array_t<double> corner_array(const V& a, const V& b, const V& c, const V& d) {
  py::array_t<double> out({py::ssize_t(4), py::ssize_t(Dims)});
  auto m = out.mutable_unchecked<2>();
  const V corners[4] = {a, b, c, d};
  for (int r = 0; r < 4; ++r)
    for (int k = 0; k < Dims; ++k) m(r, k) = corners[r][k];
  return out;
}

void bind_cots_map(py::module_& m) {
  py::class_<CotsMap>(m, "CotsMap", R"doc(
The planar COTS map of the unit square with M(0,0) = a, M(0,1) = b, M(1,1) = c, M(1,0) = d (x runs a -> d,
y runs a -> b): f + exp(x log_u + y log_v)(a - f), two commuting spirals about one fixed point, so every tile of a
regular grid is similar to every other. branches = (k_u, k_v) adds whole turns to the angles of U and V.
Refuses (ValueError naming the corners) NaN corners, coinciding adjacent corners and ranges that collapse to a curve;
parallelograms are the affine map.)doc")
      .def(py::init([](py::handle a, py::handle b, py::handle c, py::handle d, py::handle branches) {
             const auto k = to_branches(branches);
             return CotsMap(to_vec2(a, "corner a"), to_vec2(b, "corner b"), to_vec2(c, "corner c"), to_vec2(d, "corner d"),
                            k.first, k.second);
           }),
           py::arg("a"), py::arg("b"), py::arg("c"), py::arg("d"), py::arg("branches") = py::make_tuple(0, 0))
      .def_static(
          "from_spiral",
          [](py::handle a, py::handle center, std::complex<double> log_u, std::complex<double> log_v) {
            return CotsMap::from_spiral(to_vec2(a, "a"), to_vec2(center, "center"), log_u, log_v);
          },
          py::arg("a"), py::arg("center"), py::arg("log_u"), py::arg("log_v"),
          "The map center + exp(x log_u + y log_v)(a - center), any windings.")
      .def("map", [](const CotsMap& c, py::handle uv) { return map_parameters<2>(c, uv); }, py::arg("uv"),
           "Images of an N x 2 array of parameters (x, y) (or of one pair).")
      .def(
          "inverse",
          [](const CotsMap& c, py::handle points, py::handle box, bool with_branches) {
            const steady::ParameterBox pb = to_box(box);
            return preimages<2>(points, with_branches,
                                [&](const double* q) { return c.inverse(Vec2(q[0], q[1]), pb); });
          },
          py::arg("points"), py::arg("box") = py::none(), py::arg("with_branches") = false,
          "Every pre-image in [0,1]^2 (or in box = (x0, x1, y0, y1)): a K x 2 array for one point, a list of them for "
          "N x 2 points; with_branches adds the branch k of each.")
      .def(
          "tiles",
          [](const CotsMap& c, py::handle points, int nu, int nv) {
            return tiles<2>(points, [&](const double* q) { return c.tiles_of(Vec2(q[0], q[1]), nu, nv); });
          },
          py::arg("points"), py::arg("nu"), py::arg("nv"), "The tiles (i, j) of an nu x nv grid containing each point.")
      .def("field", &CotsMap::field, py::arg("x"), py::arg("y"), "The similarity V^y U^x (M(x, y) = field(x, y)(a)).")
      .def_property_readonly("u_similarity", &CotsMap::u_similarity)
      .def_property_readonly("v_similarity", &CotsMap::v_similarity)
      .def("tile_similarity", &CotsMap::tile_similarity, py::arg("i"), py::arg("j"), py::arg("nu"), py::arg("nv"))
      .def_property_readonly("area", &CotsMap::area, "Signed area of the range (closed form).")
      .def("tile_area", &CotsMap::tile_area, py::arg("i"), py::arg("j"), py::arg("nu"), py::arg("nv"))
      .def_property_readonly("corners", [](const CotsMap& c) { return corner_array<Vec2, 2>(c.a(), c.b(), c.c(), c.d()); })
      .def_property_readonly("log_u", &CotsMap::log_u)
      .def_property_readonly("log_v", &CotsMap::log_v)
      .def_property_readonly("is_affine", &CotsMap::is_affine)
      .def_property_readonly("fixed_point",
                             [](const CotsMap& c) -> py::object {
                               const auto f = c.fixed_point();
                               if (!f) return py::none();
                               return vec2_array(*f);
                             })
      .def_property_readonly("determinant", &CotsMap::determinant)
      .def_property_readonly("orientation", &CotsMap::orientation)
      .def_property_readonly("tile_angle", &CotsMap::tile_angle);
}

void bind_becots_map(py::module_& m) {
  py::class_<BecotsMap>(m, "BecotsMap", R"doc(
The BeCOTS map: M(x,y) = F + m_u^x m_v^y Rot_T(x w_u + y w_v)(a - F), with M(0,0) = a, M(0,1) = b, M(1,1) = c,
M(1,0) = d (3D corners); its range lies on the cone of apex F and axis T (a plane for coplanar corners).
raised(z) / projected(), bent(beta) / unbent().)doc")
      .def(py::init([](py::handle a, py::handle b, py::handle c, py::handle d, py::handle branches) {
             const auto k = to_branches(branches);
             return BecotsMap(to_vec3(a, "corner A"), to_vec3(b, "corner B"), to_vec3(c, "corner C"),
                              to_vec3(d, "corner D"), k.first, k.second);
           }),
           py::arg("a"), py::arg("b"), py::arg("c"), py::arg("d"), py::arg("branches") = py::make_tuple(0, 0))
      .def_static(
          "from_field",
          [](py::handle apex, py::handle axis, py::handle a, std::complex<double> log_u, std::complex<double> log_v) {
            return BecotsMap::from_field(to_vec3(apex, "apex"), to_vec3(axis, "axis"), to_vec3(a, "a"), log_u, log_v);
          },
          py::arg("apex"), py::arg("axis"), py::arg("a"), py::arg("log_u"), py::arg("log_v"))
      .def("map", [](const BecotsMap& b, py::handle uv) { return map_parameters<3>(b, uv); }, py::arg("uv"),
           "Images of an N x 2 array of parameters (x, y) (or of one pair), N x 3.")
      .def(
          "inverse",
          [](const BecotsMap& b, py::handle points, py::handle box, bool with_branches, py::handle tolerance) {
            const steady::ParameterBox pb = to_box(box);
            const double tol = tolerance.is_none() ? steady::kBecotsSurfaceTolerance : to_double(tolerance, "tolerance");
            return preimages<3>(points, with_branches,
                                [&](const double* q) { return b.inverse(Vec3(q[0], q[1], q[2]), pb, tol); });
          },
          py::arg("points"), py::arg("box") = py::none(), py::arg("with_branches") = false,
          py::arg("tolerance") = py::none(),
          "Every pre-image in [0,1]^2 (or box) of points on the range (within tolerance, relative to the corners' "
          "diameter); points off the range have none.")
      .def(
          "tiles",
          [](const BecotsMap& b, py::handle points, int nu, int nv) {
            return tiles<3>(points, [&](const double* q) { return b.tiles_of(Vec3(q[0], q[1], q[2]), nu, nv); });
          },
          py::arg("points"), py::arg("nu"), py::arg("nv"))
      .def("field", &BecotsMap::field, py::arg("x"), py::arg("y"))
      .def_property_readonly("u_similarity", &BecotsMap::u_similarity)
      .def_property_readonly("v_similarity", &BecotsMap::v_similarity)
      .def("tile_similarity", &BecotsMap::tile_similarity, py::arg("i"), py::arg("j"), py::arg("nu"), py::arg("nv"))
      .def_property_readonly("area", &BecotsMap::area, "Area of the range on its cone (closed form).")
      .def("tile_area", &BecotsMap::tile_area, py::arg("i"), py::arg("j"), py::arg("nu"), py::arg("nv"))
      .def("raised", &BecotsMap::raised, py::arg("z"))
      .def("projected", &BecotsMap::projected)
      .def("bent", &BecotsMap::bent, py::arg("beta"))
      .def("unbent", &BecotsMap::unbent)
      .def_property_readonly("bend_angle", &BecotsMap::bend_angle)
      .def_property_readonly("height", &BecotsMap::height)
      .def_property_readonly("corners",
                             [](const BecotsMap& b) { return corner_array<Vec3, 3>(b.a(), b.b(), b.c(), b.d()); })
      .def_property_readonly("axis", [](const BecotsMap& b) { return vec3_array(b.axis()); })
      .def_property_readonly("normal", [](const BecotsMap& b) { return vec3_array(b.normal()); },
                             "The unit normal of the range at A (dM/dx x dM/dy, normalized): layer_offset's direction.")
      .def_property_readonly("apex",
                             [](const BecotsMap& b) -> py::object {
                               const auto f = b.apex();
                               if (!f) return py::none();
                               return vec3_array(*f);
                             })
      .def_property_readonly("log_u", &BecotsMap::log_u)
      .def_property_readonly("log_v", &BecotsMap::log_v)
      .def_property_readonly("is_flat", &BecotsMap::is_flat)
      .def_property_readonly("shadow", &BecotsMap::shadow, "The planar map of the shadows across the axis.");
}

std::vector<Ball> to_balls(py::handle value) {
  if (py::isinstance<py::str>(value) || !py::isinstance<py::sequence>(value))
    value_error("balls", "expected a list of ((x, y, z), radius)");
  auto seq = py::reinterpret_borrow<py::sequence>(value);
  std::vector<Ball> balls;
  for (std::size_t n = 0; n < seq.size(); ++n) {
    const std::string name = "balls[" + std::to_string(n) + "]";
    auto item = py::reinterpret_borrow<py::sequence>(seq[n]);
    if (!py::isinstance<py::sequence>(seq[n]) || item.size() != 2) value_error(name, "expected ((x, y, z), radius)");
    balls.push_back({to_vec3(item[0], name + ".center"), to_double(item[1], name + ".radius")});
  }
  return balls;
}

// A pattern's counts (nu, nv) and steps (du, dv).
struct PatternGrid {
  int nu, nv;
  double du, dv;
};

PatternGrid to_grid(py::handle counts, py::handle steps) {
  if (py::isinstance<py::str>(counts) || !py::isinstance<py::sequence>(counts) || py::len(counts) != 2)
    value_error("counts", "expected (nu, nv)");
  if (py::isinstance<py::str>(steps) || !py::isinstance<py::sequence>(steps) || py::len(steps) != 2)
    value_error("steps", "expected (du, dv)");
  auto c = py::reinterpret_borrow<py::sequence>(counts);
  auto s = py::reinterpret_borrow<py::sequence>(steps);
  const auto nu = to_int(c[0], "counts[0]"), nv = to_int(c[1], "counts[1]");
  if (nu < 1 || nv < 1 || nu > 1000000000 || nv > 1000000000) value_error("counts", "each must be within 1..10^9");
  return {static_cast<int>(nu), static_cast<int>(nv), to_double(s[0], "steps[0]"), to_double(s[1], "steps[1]")};
}

py::array_t<int> pattern_ball_array(const std::vector<steady::PatternBall>& found) {
  py::array_t<int> out({py::ssize_t(found.size()), py::ssize_t(3)});
  auto m = out.mutable_unchecked<2>();
  for (std::size_t k = 0; k < found.size(); ++k) m(k, 0) = found[k].i, m(k, 1) = found[k].j, m(k, 2) = found[k].n;
  return out;
}

void bind_becots_range(py::module_& m) {
  py::class_<BecotsRangeFinder>(m, "BecotsRangeFinder", R"doc(
The BeCOTS RangeFinder: a pattern of balls whose group (i, j) is the template `balls` moved by map.field(i du, j dv)
(i < nu, j < nv), and the groups a query ball may meet, from log-polar bounds about the map's apex, in time
independent of the counts.)doc")
      .def(py::init([](const BecotsMap& map, py::handle balls, py::handle counts, py::handle steps) {
             const PatternGrid g = to_grid(counts, steps);
             return BecotsRangeFinder(map, to_balls(balls), g.nu, g.nv, g.du, g.dv);
           }),
           py::arg("map"), py::arg("balls"), py::arg("counts"), py::arg("steps"))
      .def(
          "candidates",
          [](const BecotsRangeFinder& f, py::handle center, double radius) {
            py::list out;
            for (const auto& r : f.candidates({to_vec3(center, "center"), radius}))
              out.append(py::make_tuple(r.i0, r.i1, r.j0, r.j1));
            return out;
          },
          py::arg("center"), py::arg("radius"), "Rectangles (i0, i1, j0, j1) of groups, inclusive.")
      .def(
          "interfering",
          [](const BecotsRangeFinder& f, py::handle center, double radius) {
            return pattern_ball_array(f.interfering({to_vec3(center, "center"), radius}));
          },
          py::arg("center"), py::arg("radius"), "The balls (i, j, n) that meet the query ball, as an M x 3 array.")
      .def(
          "interfering_naive",
          [](const BecotsRangeFinder& f, py::handle center, double radius) {
            return pattern_ball_array(f.interfering_naive({to_vec3(center, "center"), radius}));
          },
          py::arg("center"), py::arg("radius"))
      .def(
          "ball",
          [](const BecotsRangeFinder& f, int i, int j, int n) {
            const Ball b = f.ball(i, j, n);
            return py::make_tuple(vec3_array(b.center), b.radius);
          },
          py::arg("i"), py::arg("j"), py::arg("n"));
}

}  // namespace

// A connectivity by name ("triangle", "kagome", "honeycomb") or as (nodes (s, t), beam patterns (n1, di, dj, dk, n2)).
steady::BecotsConnectivity to_connectivity(py::handle value) {
  if (py::isinstance<py::str>(value)) return steady::becots_connectivity(value.cast<std::string>());
  if (!py::isinstance<py::sequence>(value) || py::len(value) != 2)
    value_error("connectivity", "expected 'triangle', 'kagome', 'honeycomb' or (nodes [(s, t), ...], beams)");
  auto pair = py::reinterpret_borrow<py::sequence>(value);
  steady::BecotsConnectivity cells;
  auto nodes = py::reinterpret_borrow<py::sequence>(pair[0]);
  if (!py::isinstance<py::sequence>(pair[0])) value_error("connectivity.nodes", "expected a list of (s, t)");
  for (std::size_t n = 0; n < nodes.size(); ++n)
    cells.nodes.push_back(to_vec2(nodes[n], "connectivity.nodes[" + std::to_string(n) + "]"));
  cells.beams = to_beams(pair[1]);
  return cells;
}

void bind_becots_lattice(py::module_& m) {
  m.def(
      "becots_connectivity",
      [](const std::string& name) {
        const steady::BecotsConnectivity c = steady::becots_connectivity(name);
        py::list nodes, beams;
        for (const Vec2& p : c.nodes) nodes.append(py::make_tuple(p.x, p.y));
        for (const auto& b : c.beams) beams.append(py::make_tuple(b.from, b.di, b.dj, b.dk, b.to));
        return py::make_tuple(nodes, beams);
      },
      py::arg("name"), "(nodes (s, t) in the group's parameter cell, beam patterns) of 'triangle', 'kagome', 'honeycomb'.");
  m.def(
      "becots_lattice",
      [](const BecotsMap& map, py::handle connectivity, py::handle counts, double radius, double layer_raise,
         double beam_ratio, double layer_offset) {
        return steady::becots_lattice(map, to_connectivity(connectivity), to_counts(counts), radius, layer_raise,
                                      beam_ratio, layer_offset);
      },
      py::arg("map"), py::arg("connectivity"), py::arg("counts"), py::arg("radius"), py::arg("layer_raise") = 0.0,
      py::arg("beam_ratio") = 0.0, py::arg("layer_offset") = 0.0,
      "A Lattice laid on the map's nu x nv tiles (counts (nu, nv, layers)), each layer's corner A (and its template) "
      "moved from the last by layer_raise along the axis plus layer_offset along the range's normal at A "
      "(BecotsMap.normal()); node radii `radius` scaled with the map; beams the hull of their balls, or beam_ratio "
      "times their nodes' radii. An ordinary steady brick: every query, property and output applies.");
}

void bind_becots_lattice_query(py::module_& m) {
  // Holds the lattice (keep_alive) because the query refers to it.
  py::class_<steady::BecotsLatticeQuery>(m, "BecotsLatticeQuery", R"doc(
Ball queries on a BeCOTS lattice (made by becots_lattice on `map`) through the map-level BeCOTS RangeFinder, in
time independent of the counts: only the layers of a stack whose shell of cones meets the query are searched.
Lattice.query_ball and the other queries take this path by themselves (method 'becots', auto's choice) when the
lattice is laid on a BeCOTS map.)doc")
      .def(py::init<const steady::Lattice&, const BecotsMap&>(), py::arg("lattice"), py::arg("map"),
           py::keep_alive<1, 2>())
      .def(
          "query_ball",
          [](const steady::BecotsLatticeQuery& q, py::handle center, double radius) {
            if (!(radius >= 0.0) || !std::isfinite(radius)) value_error("radius", "must be a finite number >= 0");
            steady::BallQueryResult r;
            const Ball ball{to_vec3(center, "center"), radius};
            {
              py::gil_scoped_release release;
              r = q.query_ball(ball);
            }
            return py::make_tuple(py::array_t<std::int64_t>(r.balls.size(), r.balls.data()),
                                  py::array_t<std::int64_t>(r.beams.size(), r.beams.data()));
          },
          py::arg("center"), py::arg("radius"),
          "(ball_indices, beam_indices): sorted indices of exactly the elements meeting the closed ball, as "
          "Lattice.query_ball.")
      .def(
          "candidate_groups",
          [](const steady::BecotsLatticeQuery& q, py::handle center, double radius) {
            return q.candidate_groups({to_vec3(center, "center"), radius});
          },
          py::arg("center"), py::arg("radius"))
      .def(
          "candidate_layers",
          [](const steady::BecotsLatticeQuery& q, py::handle center, double radius) {
            return q.candidate_layers({to_vec3(center, "center"), radius});
          },
          py::arg("center"), py::arg("radius"),
          "The layers whose shell of cones about the apex meets the ball: the only ones a query searches.")
      .def_property_readonly("layer_count", &steady::BecotsLatticeQuery::layer_count);
}

void bind_cots(py::module_& m) {
  bind_becots_lattice_query(m);
  bind_cots_map(m);
  bind_becots_map(m);
  bind_becots_range(m);
  bind_becots_lattice(m);
  m.def(
      "becots_pattern_properties",
      [](const BecotsMap& map, py::handle balls, py::handle counts, py::handle steps) {
        const PatternGrid g = to_grid(counts, steps);
        const steady::PatternProperties p =
            steady::becots_ball_pattern_properties(map, to_balls(balls), g.nu, g.nv, g.du, g.dv);
        py::dict out;
        out["volume"] = p.volume;
        out["area"] = p.area;
        out["centroid"] = vec3_array(p.centroid);
        return out;
      },
      py::arg("map"), py::arg("balls"), py::arg("counts"), py::arg("steps"),
      "Volume, area and centroid of the BeCOTS pattern of balls (group (i, j) = balls moved by map.field(i du, j dv)), "
      "in closed form, each ball counted whole.");
}

}  // namespace steadypy
