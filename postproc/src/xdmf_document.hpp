#pragma once
// Private to kinetofem_postproc: the XDMF 3 text that describes a results file.
//
// ResultsWriter records what it wrote (dataset paths and shapes) in a Grid per
// body and turns them into XML at commit(); nothing is read back from the HDF5
// file. Per body the document holds
//   - a Uniform grid "<body>" with the mesh, the static nodal and element
//     fields and the envelopes, and
//   - if the body has a time series, a Temporal collection "<body>_series"
//     with one Uniform grid per output time, whose attributes are hyperslabs
//     (one time step) of the (T, N, c) datasets.
// A body with one element block gets that block's topology type; a body
// with several blocks gets a Mixed topology (one ParaView block per body).
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
};

// The document; `h5_file` is the HDF5 file's name relative to the XDMF file.
std::string document(const std::string& h5_file, const std::vector<Grid>& grids);

}  // namespace kinetofem::post::xdmf
