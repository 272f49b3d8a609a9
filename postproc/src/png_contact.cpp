// The pin contact picture (png_plots.hpp): each pin's peak contact pressure and contact arc over
// the motion, from the tables contact.<body>.<joint> (pipeline/part_stress.hpp) or
// assembly.contact.<body>.<joint> (pipeline/assembly_over_motion.hpp).
#include "kinetofem/postproc/png_plots.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include <cairo.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/postproc/results_file.hpp"
#include "png_canvas.hpp"
#include "png_common.hpp"

namespace kinetofem::post {

using namespace drawing;

namespace {
std::string prefix_of(ContactTables stage) {
  switch (stage) {
    case ContactTables::PerPart:
      return "contact.";
    case ContactTables::Assembly:
      return "assembly.contact.";
  }
  return "";
}
}  // namespace

std::vector<std::string> contact_tables(const ResultsFile& results, ContactTables stage) {
  std::vector<std::string> out;
  for (const auto& name : results.tables())
    if (name.rfind(prefix_of(stage), 0) == 0) out.push_back(name);
  return out;
}

ContactPictureInfo write_contact_picture(const ResultsFile& results, const std::filesystem::path& png,
                                         const PictureOptions& options, ContactTables stage) {
  const std::string kContactTablePrefix = prefix_of(stage);
  const std::vector<std::string> names = contact_tables(results, stage);
  require(!names.empty(), "'{}' has no pin contact tables ({}<body>.<joint>: a run with load = \"contact\")",
          results.path().string(), kContactTablePrefix);
  ContactPictureInfo info;
  std::vector<Curve> pressure, arc;
  double t0 = 0.0, t1 = 0.0;
  for (const auto& name : names) {
    const FieldData table = results.read_table(name);
    require(table.values.cols() >= 4 && table.values.rows() >= 1,
            "'{}': table {} is {} x {}, expected (time, peak pressure, angle, arc) per output time",
            results.path().string(), name, table.values.rows(), table.values.cols());
    std::vector<double> t(size_t(table.values.rows())), p(t.size()), a(t.size());
    for (long k = 0; k < table.values.rows(); ++k) {
      t[size_t(k)] = table.values(k, 0);
      p[size_t(k)] = table.values(k, 1) * 1e-6;
      a[size_t(k)] = table.values(k, 3);
      if (table.values(k, 1) > info.peak_pressure_pa) {
        info.peak_pressure_pa = table.values(k, 1);
        info.peak_time_s = table.values(k, 0);
        info.peak_pin = name.substr(std::string(kContactTablePrefix).size());
      }
    }
    t0 = t.front();
    t1 = t.back();
    std::string label = name.substr(std::string(kContactTablePrefix).size());
    if (const size_t dot = label.find('.'); dot != std::string::npos) label = label.substr(0, dot) + ", pin " + label.substr(dot + 1);
    const Rgb colour = kPalette[pressure.size() % kPalette.size()];
    pressure.push_back({label, t, std::move(p), colour, false});
    arc.push_back({label, std::move(t), std::move(a), colour, false});
    info.pins.push_back(name.substr(std::string(kContactTablePrefix).size()));
  }
  Canvas canvas(options.width_px, options.height_px);
  cairo_t* cr = canvas.cr();
  title(cr, canvas,
        fmt::format("{}: pins in contact with their bores over the motion{}", case_name(results, options),
                    stage == ContactTables::Assembly ? " (the elastic assembly)" : ""),
        fmt::format("peak contact pressure {:.3f} MPa ({}, t = {:.3f} s); {:.2f} .. {:.2f} s; round pins, "
                    "frictionless (docs/contact.md)",
                    info.peak_pressure_pa * 1e-6, info.peak_pin, info.peak_time_s, t0, t1));
  const double left = 100, legend_w = 250, top = 100, bottom = 70, gap = 90;
  const double width = canvas.width() - left - legend_w - 30;
  const double panel_h = (canvas.height() - top - bottom - gap) / 2;
  const Axes ax = draw_curves(cr, Axes{left, top, width, panel_h, 0, 1, 0, 1}, pressure, "pressure [MPa]", "time [s]",
                              "Peak contact pressure on each bore", left + width + 25, {.headroom = 0.2});
  mark_point(cr, ax, ax.X(info.peak_time_s), ax.Y(info.peak_pressure_pa * 1e-6),
             fmt::format("max {:.3f} MPa at t = {:.3f} s", info.peak_pressure_pa * 1e-6, info.peak_time_s), 13, 0, -1);
  draw_curves(cr, Axes{left, top + panel_h + gap, width, panel_h, 0, 1, 0, 1}, arc, "arc [deg]", "time [s]",
              "Arc of the bore in contact", left + width + 25);
  canvas.save(png);
  return info;
}

}  // namespace kinetofem::post
