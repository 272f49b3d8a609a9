#pragma once
// CSV export of post-processed results: comma-separated, one header row whose
// column names carry their unit in brackets ("x [mm]", "von_mises [MPa]"),
// values in display units (time_history.hpp: mm, MPa, deg; others SI), '.'
// as decimal point, full double precision where it matters (%.9g).
//
//   hot spots        rank,body,node,x [mm],y [mm],z [mm],step,time [s],<field> [MPa]
//   time history     time [s],<quantity>_<component> [unit]...
//   body fields      node,x [mm],y [mm],z [mm], every static field per component,
//                    then per envelope <field>_max [unit],<field>_max_time [s]
//   mechanism        time [s], every mechanism history per component
//
// A static field's time (no series) is written as an empty cell. Every
// function throws Error naming the file if it cannot be written.
#include <filesystem>
#include <string>
#include <vector>

#include "kinetofem/postproc/hot_spots.hpp"
#include "kinetofem/postproc/time_history.hpp"

namespace kinetofem::post {

class ResultsFile;

// `units`: the SI units of the hot spot values (e.g. "Pa"); `field` names the value column.
void write_hot_spots_csv(const std::filesystem::path& path, const std::vector<HotSpot>& hot_spots,
                         const std::string& field = layout::kVonMises, const std::string& units = "Pa");

void write_history_csv(const std::filesystem::path& path, const TimeHistory& history);

// The static fields and envelopes of one body, one row per node. Scalar
// series fields without a stored envelope get a recomputed max envelope.
void write_body_fields_csv(const std::filesystem::path& path, const ResultsFile& results,
                           const std::string& body);

// Every mechanism history on the common time grid. Throws Error if the file has none.
void write_mechanism_csv(const std::filesystem::path& path, const ResultsFile& results);

}  // namespace kinetofem::post
