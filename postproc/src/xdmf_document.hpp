#pragma once
// Private to kinetofem_postproc: the XDMF 3 text that describes a results file.
//
// ResultsWriter records what it wrote (dataset paths and shapes) in a Grid per
// body and in a Mechanism, and turns them into XML at commit(); nothing is read
// back from the HDF5 file. docs/results.md ("Opening in ParaView") describes the
// document; in short, per body (one ParaView block, named after the body):
//   - without a time series: a Uniform grid "<body>" with the mesh, the static
//     nodal fields, the element fields and the envelopes;
//   - with a time series: a Temporal collection "<body>" with one Uniform grid
//     per output time, each with all of the above plus the series fields at that
//     time; if a series field is the body's geometry (SeriesField::geometry),
//     each step's Geometry is that field at that time (the same slice DataItem as
//     a series attribute; the field is an attribute too), so the body moves, and
//     the static fields and envelopes are shown on the moving geometry;
// and, if the file has mechanism histories, a grid "mechanism" (one vertex at
// the origin) whose Grid-centred attributes (ParaView field data, one row per
// mechanism time) are "time" and the histories. In a file with time steps, every
// grid without its own series (a static body, "mechanism") is a Temporal
// collection over all output times, repeating its content.
//
// The text is written so that ParaView's three XDMF readers (XDMF Reader = Xdmf2,
// Xdmf3ReaderS, Xdmf3ReaderT) read it alike (scripts/check_xdmf_paraview.py):
//   - A series field at step k is a DataItem that both libraries slice: Xdmf3
//     reads its own text "file:/dataset|start:stride:count:dataspace" (its
//     heavy-data selection syntax; Xdmf3 cannot give a HyperSlab *reference*
//     a number type, and vtkXdmf3 skips such attributes as "[None]"), Xdmf2
//     reads it as a HyperSlab (the legacy Type="HyperSlab" attribute) of its two
//     child DataItems and ignores the text.
//   - vtkXdmf3 shows only grids with a Time when a file has time steps, so static
//     content is repeated in every step, by XInclude/XPointer of the collection's
//     first step (no per-step copies of the mesh text; for a moving body two
//     includes, the Topology and the static attributes, around the step's own
//     Geometry).
//   - One Temporal collection per body, not one of Spatial collections per time:
//     both libraries make grid names unique over the document ("lever",
//     "lever[5]", ...), so per-time grid names would change the block names from
//     one time to the next; the collection's name is the block name (Xdmf2;
//     vtkXdmf3 gives these blocks no names).
//   - The Domain is never empty (Xdmf2 crashes on an empty Domain).
// A body with one element block gets that block's topology type; a body with
// several blocks gets a Mixed topology (one ParaView block per body).
#include <string>
#include <vector>

#include "kinetofem/solver/mesh.hpp"

namespace kinetofem::post::xdmf {

struct Attribute {
  std::string name;
  std::string dataset;  // path inside the HDF5 file
  fem::Index rows = 0;
  int components = 1;
  bool cell_centred = false;
  bool integer = false;
};

struct Block {
  fem::ElementType type;
  fem::Index elements = 0;
  std::string dataset;  // VTK-ordered connectivity
};

struct Grid {
  std::string name;
  fem::Index nodes = 0;
  std::string nodes_dataset;
  std::vector<Block> blocks;
  std::string mixed_dataset;  // only for several blocks
  fem::Index mixed_length = 0;
  std::vector<Attribute> attributes;  // static: nodal, element, envelopes
  std::vector<Attribute> series;      // rows = nodes; dataset is (T, N, c)
  std::vector<double> times_s;
  // Index into `series` of the (T, N, 3) field that is the geometry of each step
  // (SeriesField::geometry); -1: every step shows nodes_dataset.
  int geometry_series = -1;
};

// One mechanism history: a (rows, components) dataset over the mechanism time grid.
struct History {
  std::string name;
  std::string dataset;
  fem::Index rows = 0;
  int components = 1;
};

// The mechanism histories; no grid "mechanism" when `present` is false.
struct Mechanism {
  bool present = false;
  std::vector<double> times_s;  // /mechanism/time, written inline as the field "time"
  std::vector<History> histories;
};

// The document; `h5_file` is the HDF5 file's name relative to the XDMF file.
std::string document(const std::string& h5_file, const std::vector<Grid>& grids,
                     const Mechanism& mechanism = {});

}  // namespace kinetofem::post::xdmf
