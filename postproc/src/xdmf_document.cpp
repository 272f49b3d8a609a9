#include "xdmf_document.hpp"

#include <algorithm>
#include <set>

#include <fmt/format.h>

#include "kinetofem/postproc/markup_text.hpp"
#include "kinetofem/postproc/vtk_node_order.hpp"

namespace kinetofem::post::xdmf {

namespace {

std::string escaped(const std::string& text) { return escape_markup(text, MarkupQuotes::Any); }

// XDMF AttributeType by component count. A 6-component field (stress, strain in
// our Voigt order xx, yy, zz, xy, yz, zx) is a "Matrix", not a "Tensor6": the two
// XDMF libraries disagree on Tensor6 -- Xdmf2 (ParaView's "XDMF Reader") takes it
// as xx, xy, xz, yy, yz, zz and expands it to a 3x3, vtkXdmf3 passes the six
// values on as they are. As a Matrix both give the 6 values unchanged, which
// ParaView (like VTK) reads as the symmetric tensor XX, YY, ZZ, XY, YZ, XZ.
const char* attribute_type(int components) {
  switch (components) {
    case 1: return "Scalar";
    case 3: return "Vector";
    case 9: return "Tensor";
    default: return "Matrix";
  }
}

// Field data (the mechanism histories): no tensor types.
const char* field_attribute_type(int components) {
  return components == 1 ? "Scalar" : components == 3 ? "Vector" : "Matrix";
}

// `name`, or `name` + suffix (+ a number) if `taken` has it already; the result is added to `taken`.
std::string unique_name(const std::string& name, const std::string& suffix,
                        std::set<std::string>& taken) {
  std::string candidate = name;
  for (int n = 1; taken.contains(candidate); ++n)
    candidate = n == 1 ? name + suffix : fmt::format("{}{}{}", name, suffix, n);
  taken.insert(candidate);
  return candidate;
}

// A body as it appears in the document: XDMF attribute names made unique per centre
// (a static field that has the name of a series field becomes "<name>_static").
struct BodyView {
  const Grid* grid = nullptr;
  std::vector<std::string> static_names, series_names;
};

BodyView view_of(const Grid& grid) {
  BodyView view;
  view.grid = &grid;
  std::set<std::string> node_names, cell_names;
  if (!grid.times_s.empty())
    for (const auto& a : grid.series) view.series_names.push_back(unique_name(a.name, "_series", node_names));
  for (const auto& a : grid.attributes)
    view.static_names.push_back(
        unique_name(a.name, "_static", a.cell_centred ? cell_names : node_names));
  return view;
}

class Writer {
 public:
  explicit Writer(std::string h5_file) : h5_(escaped(h5_file)) {}

  void line(int indent, const std::string& text) {
    out_.append(size_t(2 * indent), ' ');
    out_ += text;
    out_ += '\n';
  }

  std::string hdf_item(const std::string& dims, const std::string& dataset, bool integer) const {
    return fmt::format(R"(<DataItem Dimensions="{}" NumberType="{}" Precision="8" Format="HDF">{}:{}</DataItem>)",
                       dims, integer ? "Int" : "Float", h5_, escaped(dataset));
  }

  void topology(int indent, const Grid& grid) {
    if (grid.blocks.size() == 1) {
      const Block& block = grid.blocks.front();
      const int n = fem::nodes_per_element(block.type);
      line(indent, fmt::format(R"(<Topology TopologyType="{}" NumberOfElements="{}" NodesPerElement="{}">)",
                               xdmf_topology_name(block.type), block.elements, n));
      line(indent + 1, hdf_item(fmt::format("{} {}", block.elements, n), block.dataset, true));
    } else {
      fem::Index elements = 0;
      for (const auto& block : grid.blocks) elements += block.elements;
      line(indent, fmt::format(R"(<Topology TopologyType="Mixed" NumberOfElements="{}">)", elements));
      line(indent + 1, hdf_item(fmt::format("{}", grid.mixed_length), grid.mixed_dataset, true));
    }
    line(indent, "</Topology>");
  }

  // The mesh's own coordinates (mesh/nodes).
  void geometry(int indent, const Grid& grid) {
    line(indent, R"(<Geometry GeometryType="XYZ">)");
    line(indent + 1, hdf_item(fmt::format("{} 3", grid.nodes), grid.nodes_dataset, false));
    line(indent, "</Geometry>");
  }

  // The coordinates of time step `step`: the geometry series field's slice.
  void step_geometry(int indent, const Attribute& a, size_t step, size_t steps) {
    line(indent, R"(<Geometry GeometryType="XYZ">)");
    slice_item(indent + 1, a, step, steps);
    line(indent, "</Geometry>");
  }

  void attribute_open(int indent, const std::string& name, const char* type, const char* center) {
    line(indent, fmt::format(R"(<Attribute Name="{}" AttributeType="{}" Center="{}">)",
                             escaped(name), type, center));
  }

  void static_attribute(int indent, const Attribute& a, const std::string& name) {
    attribute_open(indent, name, attribute_type(a.components), a.cell_centred ? "Cell" : "Node");
    line(indent + 1, hdf_item(fmt::format("{} {}", a.rows, a.components), a.dataset, a.integer));
    line(indent, "</Attribute>");
  }

  // One time step of a (T, N, c) dataset: start (k, 0, 0), stride 1, count (1, N, c).
  // Xdmf3 reads the DataItem's own text, "file:/dataset|start:stride:count:dataspace"
  // (Format="HDF"; Xdmf3 ignores Type); Xdmf2 reads Type="HyperSlab" (its ItemType)
  // and the two child DataItems (start/stride/count, then the whole dataset) and
  // ignores the text.
  void slice_item(int indent, const Attribute& a, size_t step, size_t steps) {
    line(indent,
         fmt::format(R"(<DataItem Type="HyperSlab" Dimensions="{1} {2}" NumberType="{3}" Precision="8" Format="HDF">{4}:{5}|{0} 0 0:1 1 1:1 {1} {2}:{6} {1} {2})",
                     step, a.rows, a.components, a.integer ? "Int" : "Float", h5_,
                     escaped(a.dataset), steps));
    line(indent + 1, fmt::format(R"(<DataItem Dimensions="3 3" NumberType="Int" Format="XML">{} 0 0 1 1 1 1 {} {}</DataItem>)",
                                 step, a.rows, a.components));
    line(indent + 1, hdf_item(fmt::format("{} {} {}", steps, a.rows, a.components), a.dataset,
                              a.integer));
    line(indent, "</DataItem>");
  }

  void step_attribute(int indent, const Attribute& a, const std::string& name, size_t step,
                      size_t steps) {
    attribute_open(indent, name, attribute_type(a.components), "Node");
    slice_item(indent + 1, a, step, steps);
    line(indent, "</Attribute>");
  }

  // The elements of a body's grid before its series fields: Topology, Geometry (of
  // step `step` for a moving body) and the static attributes.
  void body_static_content(int indent, const BodyView& body, size_t step = 0) {
    const Grid& grid = *body.grid;
    topology(indent, grid);
    if (moving(grid))
      step_geometry(indent, grid.series[size_t(grid.geometry_series)], step, grid.times_s.size());
    else
      geometry(indent, grid);
    for (size_t i = 0; i < grid.attributes.size(); ++i)
      static_attribute(indent, grid.attributes[i], body.static_names[i]);
  }

  // The same for step k > 0, including the repeated part from step 0: everything
  // but a moving body's Geometry. Children of a step grid: 1 Time, 2 Topology,
  // 3 Geometry, 4... static attributes.
  void body_static_content_included(int indent, const BodyView& body, size_t step) {
    const Grid& grid = *body.grid;
    const size_t last = 3 + grid.attributes.size();
    if (!moving(grid)) {
      include(indent, grid.name, 2, last);
      return;
    }
    include(indent, grid.name, 2, 2);
    step_geometry(indent, grid.series[size_t(grid.geometry_series)], step, grid.times_s.size());
    if (!grid.attributes.empty()) include(indent, grid.name, 4, last);
  }

  static bool moving(const Grid& grid) {
    return grid.geometry_series >= 0 && !grid.times_s.empty();
  }

  // The grid of the mechanism histories: one vertex at the origin, the histories and
  // their time as Grid-centred attributes (ParaView field data, one row per time).
  void mechanism_content(int indent, const Mechanism& m) {
    line(indent, R"(<Topology TopologyType="Polyvertex" NumberOfElements="1" NodesPerElement="1">)");
    line(indent + 1, R"(<DataItem Dimensions="1 1" NumberType="Int" Format="XML">0</DataItem>)");
    line(indent, "</Topology>");
    line(indent, R"(<Geometry GeometryType="XYZ">)");
    line(indent + 1, R"(<DataItem Dimensions="1 3" NumberType="Float" Precision="8" Format="XML">0 0 0</DataItem>)");
    line(indent, "</Geometry>");
    if (m.times_s.empty()) return;
    // Inline, because /mechanism/time is one-dimensional and Xdmf3 would read a
    // Grid-centred (T) item as one tuple of T components; (T, 1) reads alike everywhere.
    attribute_open(indent, "time", "Scalar", "Grid");
    line(indent + 1, fmt::format(R"(<DataItem Dimensions="{} 1" NumberType="Float" Precision="8" Format="XML">)",
                                 m.times_s.size()));
    constexpr size_t per_line = 10;
    for (size_t i = 0; i < m.times_s.size(); i += per_line) {
      std::string values;
      for (size_t j = i; j < std::min(m.times_s.size(), i + per_line); ++j)
        values += fmt::format("{}{}", j == i ? "" : " ", m.times_s[j]);  // shortest exact text
      line(indent + 2, values);
    }
    line(indent + 1, "</DataItem>");
    line(indent, "</Attribute>");
    for (const auto& h : m.histories) {
      if (h.name == "time") continue;  // reserved by ResultsWriter; never happens
      attribute_open(indent, h.name, field_attribute_type(h.components), "Grid");
      line(indent + 1, hdf_item(fmt::format("{} {}", h.rows, h.components), h.dataset, false));
      line(indent, "</Attribute>");
    }
  }

  // <xi:include> of children `first` to `last` (1-based, 1 is the Time; last 0: to
  // the end) of the first step of temporal collection `collection`.
  void include(int indent, const std::string& collection, size_t first, size_t last) {
    const std::string which =
        first == last ? fmt::format("position() = {}", first)
        : last == 0   ? fmt::format("position() &gt; {}", first - 1)
                      : fmt::format("position() &gt; {} and position() &lt;= {}", first - 1, last);
    line(indent, fmt::format(R"x(<xi:include xpointer="xpointer(/Xdmf/Domain/Grid[@Name='{}']/Grid[1]/*[{}])"/>)x",
                             escaped(collection), which));
  }

  std::string take() { return std::move(out_); }

 private:
  std::string h5_;
  std::string out_;
};

// The name of the mechanism grid: "mechanism" unless a body has that name.
std::string mechanism_grid_name(const std::vector<Grid>& grids) {
  std::set<std::string> taken;
  for (const auto& g : grids) taken.insert(g.name);
  return unique_name("mechanism", "_histories", taken);
}

}  // namespace

std::string document(const std::string& h5_file, const std::vector<Grid>& grids,
                     const Mechanism& mechanism) {
  Writer w(h5_file);
  std::vector<BodyView> bodies;
  for (const Grid& grid : grids) bodies.push_back(view_of(grid));
  const std::string mechanism_name = mechanism_grid_name(grids);

  // Output times of all series, ascending (each body's times increase strictly).
  std::vector<double> times;
  for (const Grid& grid : grids) times.insert(times.end(), grid.times_s.begin(), grid.times_s.end());
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());

  // A grid without time steps: the grid itself in a file without time steps; in a
  // file with time steps a Temporal collection over all output times, the first
  // step with the content and the others including it (vtkXdmf3 leaves grids
  // without a Time out as soon as a file has time steps).
  auto timeless = [&](const std::string& name, auto&& content) {
    if (times.empty()) {
      w.line(2, fmt::format(R"(<Grid Name="{}" GridType="Uniform">)", escaped(name)));
      content(3);
      w.line(2, "</Grid>");
      return;
    }
    w.line(2, fmt::format(R"(<Grid Name="{}" GridType="Collection" CollectionType="Temporal">)",
                          escaped(name)));
    for (size_t j = 0; j < times.size(); ++j) {
      w.line(3, fmt::format(R"(<Grid Name="{}_step{}" GridType="Uniform">)", escaped(name), j));
      w.line(4, fmt::format(R"(<Time Value="{}"/>)", times[j]));
      if (j == 0)
        content(4);
      else
        w.include(4, name, 2, 0);
      w.line(3, "</Grid>");
    }
    w.line(2, "</Grid>");
  };

  w.line(0, R"(<?xml version="1.0" encoding="utf-8"?>)");
  w.line(0, R"(<Xdmf Version="3.0" xmlns:xi="http://www.w3.org/2001/XInclude">)");
  w.line(1, "<Domain>");
  for (const BodyView& body : bodies) {
    const Grid& grid = *body.grid;
    if (grid.times_s.empty()) {
      timeless(grid.name, [&](int indent) { w.body_static_content(indent, body); });
      continue;
    }
    // A body with a time series: one Uniform grid per output time of the body.
    w.line(2, fmt::format(R"(<Grid Name="{}" GridType="Collection" CollectionType="Temporal">)",
                          escaped(grid.name)));
    for (size_t k = 0; k < grid.times_s.size(); ++k) {
      w.line(3, fmt::format(R"(<Grid Name="{}_step{}" GridType="Uniform">)", escaped(grid.name), k));
      // Shortest text that reads back as the same double.
      w.line(4, fmt::format(R"(<Time Value="{}"/>)", grid.times_s[k]));
      if (k == 0)
        w.body_static_content(4, body);
      else
        w.body_static_content_included(4, body, k);
      for (size_t i = 0; i < grid.series.size(); ++i)
        w.step_attribute(4, grid.series[i], body.series_names[i], k, grid.times_s.size());
      w.line(3, "</Grid>");
    }
    w.line(2, "</Grid>");
  }
  if (mechanism.present)
    timeless(mechanism_name, [&](int indent) { w.mechanism_content(indent, mechanism); });
  if (bodies.empty() && !mechanism.present)  // Xdmf2 crashes on an empty Domain
    w.line(2, R"(<Grid Name="results" GridType="Collection" CollectionType="Spatial"/>)");
  w.line(1, "</Domain>");
  w.line(0, "</Xdmf>");
  return w.take();
}

}  // namespace kinetofem::post::xdmf
