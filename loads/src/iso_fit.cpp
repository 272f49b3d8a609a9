#include "kinetofem/loads/iso_fit.hpp"

#include <array>
#include <cctype>

#include "kinetofem/core/error.hpp"

namespace kinetofem::loads {

namespace {

constexpr int kRanges = 13;
// Upper limits of the nominal diameter ranges (mm); the first starts at 1.
constexpr std::array<double, kRanges> kUpperMm = {3, 6, 10, 18, 30, 50, 80, 120, 180, 250, 315, 400, 500};

struct Grade {
  int grade;
  std::array<int, kRanges> micrometres;
};
// Standard tolerance grades IT (ISO 286-1, table 1), um.
constexpr std::array<Grade, 5> kGrades = {{
    {6, {6, 8, 9, 11, 13, 16, 19, 22, 25, 29, 32, 36, 40}},
    {7, {10, 12, 15, 18, 21, 25, 30, 35, 40, 46, 52, 57, 63}},
    {8, {14, 18, 22, 27, 33, 39, 46, 54, 63, 72, 81, 89, 97}},
    {9, {25, 30, 36, 43, 52, 62, 74, 87, 100, 115, 130, 140, 155}},
    {11, {60, 75, 90, 110, 130, 160, 190, 220, 250, 290, 320, 360, 400}},
}};

struct Deviation {
  char letter;
  std::array<int, kRanges> micrometres;  // upper deviation es of the shaft (<= 0)
};
// Fundamental deviations of shafts d .. h (ISO 286-1, table 2), um. The
// ranges above 10 mm group pairs of the table's subranges, whose values
// agree for these letters.
constexpr std::array<Deviation, 5> kShafts = {{
    {'d', {-20, -30, -40, -50, -65, -80, -100, -120, -145, -170, -190, -210, -230}},
    {'e', {-14, -20, -25, -32, -40, -50, -60, -72, -85, -100, -110, -125, -135}},
    {'f', {-6, -10, -13, -16, -20, -25, -30, -36, -43, -50, -56, -62, -68}},
    {'g', {-2, -4, -5, -6, -7, -9, -10, -12, -14, -15, -17, -18, -20}},
    {'h', {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}},
}};

struct ParsedFit {
  int hole_grade = 0;
  char shaft_letter = 0;
  int shaft_grade = 0;
};

const Grade* grade(int g) {
  for (const auto& x : kGrades)
    if (x.grade == g) return &x;
  return nullptr;
}

const Deviation* shaft(char letter) {
  for (const auto& x : kShafts)
    if (x.letter == letter) return &x;
  return nullptr;
}

// "H7/g6" -> {7, 'g', 6}; false when it is not of that form.
bool parse(const std::string& fit, ParsedFit& out) {
  const auto slash = fit.find('/');
  if (slash == std::string::npos || slash < 2 || slash + 2 >= fit.size() + 1) return false;
  const std::string hole = fit.substr(0, slash), shaft_part = fit.substr(slash + 1);
  if (hole.size() < 2 || hole[0] != 'H' || shaft_part.size() < 2) return false;
  auto number = [](const std::string& s, int& value) {
    if (s.empty() || s.size() > 2) return false;
    for (const char c : s)
      if (!std::isdigit(static_cast<unsigned char>(c))) return false;
    value = std::stoi(s);
    return true;
  };
  if (!number(hole.substr(1), out.hole_grade)) return false;
  out.shaft_letter = shaft_part[0];
  return number(shaft_part.substr(1), out.shaft_grade);
}

}  // namespace

void check_fit(const std::string& fit) {
  ParsedFit p;
  require(parse(fit, p) && grade(p.hole_grade) && shaft(p.shaft_letter) && grade(p.shaft_grade),
          "fit \"{}\": not a supported ISO 286 clearance fit; give a hole H6 .. H9 or H11 and a shaft d, e, f, g or h "
          "of grade 6 .. 9 or 11, e.g. \"H7/g6\" or \"H8/f7\" (interference and transition fits are not supported)",
          fit);
}

FitClearance fit_clearance(const std::string& fit, double diameter_m) {
  check_fit(fit);
  ParsedFit p;
  parse(fit, p);
  const double d_mm = diameter_m * 1e3;
  require(d_mm >= 1.0 && d_mm <= kUpperMm.back(), "fit \"{}\": the bore's diameter {:.3g} mm is outside the ISO 286 "
          "tables used here (1 .. 500 mm)", fit, d_mm);
  int range = 0;
  while (d_mm > kUpperMm[size_t(range)]) ++range;
  const double hole_upper = grade(p.hole_grade)->micrometres[size_t(range)];  // hole: 0 .. IT
  const double shaft_upper = shaft(p.shaft_letter)->micrometres[size_t(range)];
  const double shaft_lower = shaft_upper - grade(p.shaft_grade)->micrometres[size_t(range)];
  return {(0.0 - shaft_upper) * 1e-6, (hole_upper - shaft_lower) * 1e-6};
}

double radial_clearance(double clearance_m, const std::string& fit, double bore_diameter_m) {
  return fit.empty() ? clearance_m : fit_clearance(fit, bore_diameter_m).mean_radial_m();
}

}  // namespace kinetofem::loads
