#include "kinetofem/postproc/csv_export.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>

#include "kinetofem/core/error.hpp"
#include "kinetofem/postproc/results_file.hpp"

namespace kinetofem::post {

namespace {

// A CSV file being written; throws Error naming the file on any failure.
class CsvFile {
 public:
  explicit CsvFile(const std::filesystem::path& path)
      : path_(path), file_(std::fopen(path.string().c_str(), "w"), &std::fclose) {
    if (!file_) fail("{}: cannot write the CSV file: {}", path.string(), std::strerror(errno));
  }
  void row(const std::vector<std::string>& cells) {
    std::string line;
    for (size_t i = 0; i < cells.size(); ++i) line += (i ? "," : "") + cells[i];
    line += '\n';
    if (std::fwrite(line.data(), 1, line.size(), file_.get()) != line.size())
      fail("{}: write failed: {}", path_.string(), std::strerror(errno));
  }
  void close() {
    if (std::fclose(file_.release()) != 0)
      fail("{}: write failed on close: {}", path_.string(), std::strerror(errno));
  }

 private:
  std::filesystem::path path_;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file_;
};

std::string number(double v) {
  if (std::isnan(v)) return "";
  if (v == 0.0) v = 0.0;  // no "-0" cells
  return fmt::format("{:.9g}", v);
}

std::string header(const std::string& name, const std::string& unit) {
  return unit.empty() || unit == layout::kDimensionless ? name : fmt::format("{} [{}]", name, unit);
}

// Column headers of a c-component field, e.g. displacement_x [mm].
std::vector<std::string> component_headers(const std::string& name, const std::string& unit,
                                           const std::vector<std::string>& components, long c) {
  std::vector<std::string> out;
  if (c == 1 && components.size() <= 1) return {header(name, unit)};
  for (long i = 0; i < c; ++i) {
    const std::string component = size_t(i) < components.size() ? components[size_t(i)] : std::to_string(i);
    out.push_back(header(name + "_" + component, unit));
  }
  return out;
}

}  // namespace

void write_hot_spots_csv(const std::filesystem::path& path, const std::vector<HotSpot>& hot_spots,
                         const std::string& field, const std::string& units) {
  const DisplayUnit u = display_unit(units);
  CsvFile csv(path);
  csv.row({"rank", "body", "node", "x [mm]", "y [mm]", "z [mm]", "step", "time [s]", header(field, u.label), "solid",
           "seam"});
  for (size_t i = 0; i < hot_spots.size(); ++i) {
    const HotSpot& s = hot_spots[i];
    csv.row({std::to_string(i + 1), s.body, std::to_string(s.node), number(s.position_m.x() * 1e3),
             number(s.position_m.y() * 1e3), number(s.position_m.z() * 1e3),
             s.step < 0 ? "" : std::to_string(s.step), number(s.time_s), number(s.value * u.factor), s.solid,
             s.seam});
  }
  csv.close();
}

void write_history_csv(const std::filesystem::path& path, const TimeHistory& history) {
  const DisplayUnit u = display_unit(history.units);
  CsvFile csv(path);
  std::vector<std::string> head = {"time [s]"};
  for (auto& h : component_headers(history.quantity, u.label, history.component_names, long(history.values.cols())))
    head.push_back(h);
  csv.row(head);
  for (size_t k = 0; k < history.time_s.size(); ++k) {
    std::vector<std::string> cells = {number(history.time_s[k])};
    for (long c = 0; c < history.values.cols(); ++c) cells.push_back(number(history.values(long(k), c) * u.factor));
    csv.row(cells);
  }
  csv.close();
}

void write_body_fields_csv(const std::filesystem::path& path, const ResultsFile& results,
                           const std::string& body) {
  const fem::NodeCoordinates nodes = results.read_mesh(body).nodes;
  const fem::Index n = nodes.rows();
  struct Column {
    std::vector<std::string> headers;
    FieldMatrix values;  // N x c, display units
  };
  std::vector<Column> columns;
  for (const auto& name : results.static_fields(body)) {
    const FieldData f = results.read_static(body, name);
    const DisplayUnit u = display_unit(f.units);
    columns.push_back({component_headers(name, u.label, f.component_names, long(f.values.cols())), f.values * u.factor});
  }
  const std::vector<double> times = results.series_times(body);
  auto add_envelope = [&](const std::string& name, const std::string& units, const FieldMatrix& value,
                          const IndexMatrix& step, const std::vector<double>& times) {
    const DisplayUnit u = display_unit(units);
    Column v{component_headers(name + "_max", u.label, {}, long(value.cols())), value * u.factor};
    Column t{component_headers(name + "_max_time", "s", {}, long(step.cols())), FieldMatrix(step.rows(), step.cols())};
    for (long i = 0; i < step.rows(); ++i)
      for (long c = 0; c < step.cols(); ++c) {
        const fem::Index k = step(i, c);
        t.values(i, c) = k >= 0 && size_t(k) < times.size() ? times[size_t(k)] : std::nan("");
      }
    columns.push_back(std::move(v));
    columns.push_back(std::move(t));
  };
  const auto stored = results.envelopes(body);
  for (const auto& name : stored) {
    const EnvelopeData e = results.read_envelope(body, name);
    add_envelope(e.operation == layout::kEnvelopeMax ? name : name + "_" + e.operation, e.units, e.values, e.step, e.times_s);
  }
  for (const auto& name : results.series_fields(body)) {
    if (std::find(stored.begin(), stored.end(), name) != stored.end()) continue;
    if (results.read_step(body, name, 0).values.cols() != 1) continue;
    const BodyEnvelope e = envelope_from_series(results, body, name);
    IndexMatrix step(n, 1);
    for (fem::Index i = 0; i < n; ++i) step(i, 0) = e.max_step[size_t(i)];
    add_envelope(name, e.units, e.max_value, step, times);
  }
  for (const Column& c : columns)
    require(c.values.rows() == n, "body '{}': field '{}' has {} rows for {} nodes", body,
            c.headers.front(), c.values.rows(), n);

  CsvFile csv(path);
  std::vector<std::string> head = {"node", "x [mm]", "y [mm]", "z [mm]"};
  for (const Column& c : columns) head.insert(head.end(), c.headers.begin(), c.headers.end());
  csv.row(head);
  std::vector<std::string> cells;
  for (fem::Index i = 0; i < n; ++i) {
    cells = {std::to_string(i), number(nodes(i, 0) * 1e3), number(nodes(i, 1) * 1e3), number(nodes(i, 2) * 1e3)};
    for (const Column& c : columns)
      for (long j = 0; j < c.values.cols(); ++j) cells.push_back(number(c.values(i, j)));
    csv.row(cells);
  }
  csv.close();
}

void write_mechanism_csv(const std::filesystem::path& path, const ResultsFile& results) {
  const auto names = results.histories();
  require(!names.empty(), "'{}' has no mechanism histories", results.path().string());
  std::vector<TimeHistory> histories;
  for (const auto& name : names) histories.push_back(mechanism_history(results, name));
  CsvFile csv(path);
  std::vector<std::string> head = {"time [s]"};
  for (const auto& h : histories)
    for (auto& c : component_headers(h.quantity, display_unit(h.units).label, h.component_names, long(h.values.cols())))
      head.push_back(c);
  csv.row(head);
  const std::vector<double>& t = histories.front().time_s;
  for (size_t k = 0; k < t.size(); ++k) {
    std::vector<std::string> cells = {number(t[k])};
    for (const auto& h : histories) {
      const double f = display_unit(h.units).factor;
      for (long c = 0; c < h.values.cols(); ++c) cells.push_back(number(h.values(long(k), c) * f));
    }
    csv.row(cells);
  }
  csv.close();
}

}  // namespace kinetofem::post
