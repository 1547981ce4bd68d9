#include "calibrate/export/export_notes.hpp"

#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "store/version.hpp"

namespace seedcal {

std::string exact_number_text(double v) {
  char buf[40];
  for (int precision = 6; precision <= 17; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}

std::vector<std::string> provenance_lines(const ExportedModel& m) {
  std::vector<std::string> out;
  if (!m.study_name.empty()) {
    out.push_back("study \"" + m.study_name + "\" (" + m.study_dir + ")" +
                  (m.converged ? "" : ": its confirmation did not converge to the tolerance (summary.json: converged)"));
    out.push_back("clump model \"" + m.model_name + "\": " + m.model_reason);
    out.push_back("values: the scene of test \"" + m.test_name + "\" (" + m.scene_path +
                  ") with the study's values in place:");
    for (const auto& [path, v] : m.calibrated.items())
      out.push_back("  " + path + " = " + exact_number_text(v.get<double>()) + " (calibrated)");
    for (const auto& [path, v] : m.held_at_nominal.items())
      out.push_back("  " + path + " = " + exact_number_text(v.get<double>()) + " (held at its nominal value)");
    for (const std::string& w : m.warnings) out.push_back("the study's scenes warned (the values were fitted on this rig): " + w);
  } else {
    out.push_back("values: the scene " + m.scene_path);
  }
  out.push_back("clump: " + m.particle_description + ", " + std::to_string(m.seeds.body.spheres.size()) +
                " spheres, in its principal frame (centre of mass at the origin)");
  out.push_back("written by seedcal " + version_string());
  return out;
}

std::vector<std::string> carry_over_notes(const ExportedModel& m) {
  const ContactOptions& c = m.physics.contact;
  std::vector<std::string> n;
  if (c.normal == NormalModel::hmnr)
    n.push_back("Contact model: HMNR (seedcal's multi-contact restitution correction: each damper of a body pair "
                "touching at n spheres at once divided by sqrt(n)) has no LIGGGHTS equivalent. The fragment uses "
                "plain Hertz (model hertz), under which a clump landing on several spheres at once rebounds below "
                "the set restitution.");
  if (c.rolling == RollingModel::cdt) {
    std::string s =
        "Rolling friction: LIGGGHTS's cdt uses the relative spin of the two bodies (w_i - w_j), the reduced radius "
        "R* of the two spheres and the elastic part of the normal force; seedcal's CDT uses each body's own spin "
        "w_i, |Fn|, and the lever R_i = ";
    s += c.cdt_lever_from_centre_of_mass
             ? "the distance of the contact point from the body's centre of mass (rolling_lever = centre_of_mass)"
             : "the contacting sphere's radius less half the overlap (rolling_lever = sphere)";
    if (c.cdt_stop_limit)
      s += ", and it holds a body at rest (cdt_at_rest = static) where the sign function w/|w| flips every step";
    n.push_back(s + ".");
  } else if (c.rolling == RollingModel::epsd) {
    n.push_back("Rolling friction: seedcal's EPSD and LIGGGHTS's epsd are the type C model of Ai et al. (2011), "
                "k_r = 2.25 k_n mu_r^2 R*^2, with the rolling damping ratio " + exact_number_text(c.epsd_damping_ratio) +
                " (coefficientRollingViscousDamping); how each code updates the rolling spring within a step may "
                "differ in detail.");
  }
  n.push_back("Sliding: both cap the tangential force at mu_s |Fn|; at the cap seedcal resets the spring to carry the "
              "limit alone, LIGGGHTS to carry the limit plus the damping force.");
  if (c.dashpot_predicted)
    n.push_back("Dashpots: the scene sets dashpot_velocity = predicted (the end-of-step velocity); LIGGGHTS's "
                "dashpots see the half-step velocity.");
  const ScaleDistribution& sc = m.seeds.scale;
  if (sc.sd > 0.0)
    n.push_back("Size spread: the scene scales each seed by a normal factor (mean 1, sd " + exact_number_text(sc.sd) +
                ", truncated to [" + exact_number_text(sc.lo) + ", " + exact_number_text(sc.hi) +
                "]); the template is exported at scale 1, so LIGGGHTS pours seeds of one size. Templates at other "
                "scales in the particledistribution/discrete would approximate the spread.");
  bool placeholder = false;
  for (std::uint16_t a = 0; a < m.physics.materials.size(); ++a)
    for (std::uint16_t b = a; b < m.physics.materials.size(); ++b) placeholder = placeholder || !m.interaction(a, b);
  if (placeholder)
    n.push_back("Material pairs without an [[interaction]] in the scene get placeholder coefficients in the "
                "peratomtypepair tables (seedcal lets no such pair touch).");
  return n;
}

std::string comment_block(const std::vector<std::string>& lines, const std::string& marker, std::size_t width) {
  std::string out;
  for (const std::string& line : lines) {
    // The line's own indentation is kept; continuation lines hang under its text (after a "- ").
    std::size_t lead = line.find_first_not_of(' ');
    if (lead == std::string::npos) lead = 0;
    const std::size_t indent = lead + (line.compare(lead, 2, "- ") == 0 ? 2 : 0);
    std::istringstream words(line);
    std::string word, current(lead, ' ');
    bool first = true;
    while (words >> word) {
      if (!first && current.size() + 1 + word.size() > width) {
        out += marker + current + "\n";
        current = std::string(indent, ' ') + word;
      } else {
        current += (first ? "" : " ") + word;
      }
      first = false;
    }
    out += (current.empty() ? marker.substr(0, marker.find_last_not_of(' ') + 1) : marker + current) + "\n";
  }
  return out;
}

}  // namespace seedcal
