#include "xdmf_document.hpp"

#include <fmt/format.h>

#include "kinetofem/postproc/vtk_node_order.hpp"

namespace kinetofem::post::xdmf {

namespace {

std::string escaped(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

// XDMF AttributeType by component count; Tensor6 is the symmetric tensor in
// the order xx, yy, zz, xy, yz, xz, which is our Voigt order.
const char* attribute_type(int components) {
  switch (components) {
    case 1: return "Scalar";
    case 3: return "Vector";
    case 6: return "Tensor6";
    case 9: return "Tensor";
    default: return "Matrix";
  }
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

  void mesh(int indent, const Grid& grid) {
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
    line(indent, R"(<Geometry GeometryType="XYZ">)");
    line(indent + 1, hdf_item(fmt::format("{} 3", grid.nodes), grid.nodes_dataset, false));
    line(indent, "</Geometry>");
  }

  void attribute_open(int indent, const Attribute& a) {
    line(indent, fmt::format(R"(<Attribute Name="{}" AttributeType="{}" Center="{}">)",
                             escaped(a.name), attribute_type(a.components),
                             a.cell_centred ? "Cell" : "Node"));
  }

  void static_attribute(int indent, const Attribute& a) {
    attribute_open(indent, a);
    line(indent + 1, hdf_item(fmt::format("{} {}", a.rows, a.components), a.dataset, a.integer));
    line(indent, "</Attribute>");
  }

  // One time step of a (T, N, c) dataset: start (k, 0, 0), stride 1, count (1, N, c).
  void step_attribute(int indent, const Attribute& a, size_t step, size_t steps) {
    attribute_open(indent, a);
    line(indent + 1, fmt::format(R"(<DataItem ItemType="HyperSlab" Dimensions="{} {}" Type="HyperSlab">)",
                                 a.rows, a.components));
    line(indent + 2, fmt::format(R"(<DataItem Dimensions="3 3" NumberType="Int" Format="XML">{} 0 0 1 1 1 1 {} {}</DataItem>)",
                                 step, a.rows, a.components));
    line(indent + 2, hdf_item(fmt::format("{} {} {}", steps, a.rows, a.components), a.dataset,
                              a.integer));
    line(indent + 1, "</DataItem>");
    line(indent, "</Attribute>");
  }

  std::string take() { return std::move(out_); }

 private:
  std::string h5_;
  std::string out_;
};

}  // namespace

std::string document(const std::string& h5_file, const std::vector<Grid>& grids) {
  Writer w(h5_file);
  w.line(0, R"(<?xml version="1.0" encoding="utf-8"?>)");
  w.line(0, R"(<Xdmf Version="3.0" xmlns:xi="http://www.w3.org/2001/XInclude">)");
  w.line(1, "<Domain>");
  for (const Grid& grid : grids) {
    w.line(2, fmt::format(R"(<Grid Name="{}" GridType="Uniform">)", escaped(grid.name)));
    w.mesh(3, grid);
    for (const auto& a : grid.attributes) w.static_attribute(3, a);
    w.line(2, "</Grid>");
    if (grid.times_s.empty()) continue;
    w.line(2, fmt::format(R"(<Grid Name="{}_series" GridType="Collection" CollectionType="Temporal">)",
                          escaped(grid.name)));
    for (size_t k = 0; k < grid.times_s.size(); ++k) {
      w.line(3, fmt::format(R"(<Grid Name="{}_step{}" GridType="Uniform">)", escaped(grid.name), k));
      // Shortest text that reads back as the same double.
      w.line(4, fmt::format(R"(<Time Value="{}"/>)", grid.times_s[k]));
      w.mesh(4, grid);
      for (const auto& a : grid.series) w.step_attribute(4, a, k, grid.times_s.size());
      w.line(3, "</Grid>");
    }
    w.line(2, "</Grid>");
  }
  w.line(1, "</Domain>");
  w.line(0, "</Xdmf>");
  return w.take();
}

}  // namespace kinetofem::post::xdmf
