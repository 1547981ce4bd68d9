#include "reports/studies_report.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "reports/report.hpp"
#include "reports/sections/common.hpp"
#include "store/errors.hpp"
#include "store/version.hpp"

namespace seedcal::reports {
namespace {

const std::vector<std::string> kKinds = {"multicontact", "stiffness", "tradeoff", "trend", "moisture"};

nlohmann::json read_json(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  try {
    return nlohmann::json::parse(text.str());
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path + ": not a study result (" + std::string(e.what()) + ")");
  }
}

std::string mm(const nlohmann::json& metres) {
  const double v = as_number(metres);
  return std::isfinite(v) ? format_number(1000.0 * v, 4) : "n/a";
}

// Free drop (and drum) under HM and HMNR: the paper's section 4.
void add_multicontact(const nlohmann::json& j, Document& doc) {
  Section s{"multicontact", "Multi-contact study: Hertz-Mindlin (HM) against HMNR", {}};
  s.paragraph("Free drop from 150 mm, " + format_value(j.value("repeats", nlohmann::json())) +
              " repeats; the same seeds (orientations) under both models. Overrides: " +
              format_value(j.value("sets", nlohmann::json::array())) + ".");
  const auto& fd = member(j, "free_drop");
  const auto& paper = member(fd, "paper");
  Table t{"multicontact", "Rebound height and contact points at impact", {"test", "model", "index", "mean", "sd", "n", "paper mean", "paper sd"}, {}, {}};
  for (const char* m : {"hertz_mindlin", "hmnr"}) {
    const std::string label = std::string(m) == "hmnr" ? "HMNR" : "HM";
    const auto& h = member(member(fd, m), "rebound_height_m");
    t.add_row({"free drop", label, "rebound height, mm", mm(h["mean"]), mm(h["sd"]), format_value(h.value("n", nlohmann::json())),
               mm(paper.value(std::string(m) + "_rebound_height_m", nlohmann::json())), mm(paper.value(std::string(m) + "_sd_m", nlohmann::json()))});
    const auto& c = member(member(fd, m), "contact_points");
    t.add_row({"free drop", label, "contact points", format_value(c.value("mean", nlohmann::json())), format_value(c.value("sd", nlohmann::json())),
               format_value(c.value("n", nlohmann::json())), "not given", "not given"});
  }
  const auto& drum = member(j, "drum");
  for (const char* m : {"hertz_mindlin", "hmnr"}) {
    if (drum.is_null()) break;
    const std::string label = std::string(m) == "hmnr" ? "HMNR" : "HM";
    const auto& a = member(member(drum, m), "dynamic_angle_of_repose_deg");
    const auto& p = member(drum, "paper");
    t.add_row({"drum", label, "dynamic angle of repose, deg", format_value(a.value("mean", nlohmann::json())), format_value(a.value("sd", nlohmann::json())),
               format_value(a.value("n", nlohmann::json())), format_value(p.value(std::string(m) + "_deg", nlohmann::json())),
               format_value(p.value(std::string(m) + "_sd_deg", nlohmann::json()))});
  }
  t.notes.push_back("HMNR against HM, rebound: " + format_percent(fd.value("rebound_relative_difference", nlohmann::json())) +
                    (drum.is_null() ? std::string() : "; drum angle: " + format_percent(drum.value("angle_relative_difference", nlohmann::json()))) +
                    ". Paper: " + format_value(paper.value("note", nlohmann::json(""))) + ".");
  s.table(std::move(t));

  // Every drop under both models (the same seed on one x), the paper's means as lines.
  const auto hm = member(member(member(fd, "hertz_mindlin"), "rebound_height_m"), "samples");
  const auto nr = member(member(member(fd, "hmnr"), "rebound_height_m"), "samples");
  if (hm.is_array() && nr.is_array() && !hm.empty() && hm.size() == nr.size()) {
    std::vector<std::vector<double>> rows;
    for (std::size_t i = 0; i < hm.size(); ++i) rows.push_back({static_cast<double>(i + 1), 1000.0 * as_number(hm[i]), 1000.0 * as_number(nr[i])});
    GnuplotPlot p;
    p.add_data("drops.dat", rows);
    const double phm = 1000.0 * as_number(paper.value("hertz_mindlin_rebound_height_m", nlohmann::json()));
    const double pnr = 1000.0 * as_number(paper.value("hmnr_rebound_height_m", nlohmann::json()));
    p.script = "set title 'Free drop from 150 mm: rebound height of every drop'\nset xlabel 'drop (seed)'\n"
               "set ylabel 'rebound height (mm)'\nset grid\nset key outside right top vertical\nset offsets 0.5, 0.5, 0, 0\n"
               "plot 'drops.dat' using 1:2 with points pt 6 ps 2.2 lw 2 lc rgb '#1f77b4' title 'HM', "
               "'drops.dat' using 1:3 with points pt 5 ps 1.3 lc rgb '#d62728' title 'HMNR'";
    if (std::isfinite(phm)) p.script += ", " + gp_number(phm) + " with lines dt 2 lc rgb '#1f77b4' title 'paper HM'";
    if (std::isfinite(pnr)) p.script += ", " + gp_number(pnr) + " with lines dt 2 lc rgb '#d62728' title 'paper HMNR'";
    p.script += "\n";
    add_plot(s, "multicontact_drops", "Rebound height of each drop under HM and HMNR, with the paper's means", p);
  }
  doc.sections.push_back(std::move(s));
}

// Free drop under HMNR at several Young's moduli: the paper's Figure 26.
void add_stiffness(const nlohmann::json& j, Document& doc) {
  Section s{"stiffness", "Stiffness study: contact points and rebound height against E", {}};
  s.paragraph("Free drop under HMNR, " + format_value(j.value("repeats", nlohmann::json())) + " repeats per modulus. Paper: " +
              format_value(j.value("paper", nlohmann::json(""))) + ".");
  Table t{"stiffness", "Per Young's modulus", {"E, Pa", "contact points", "sd", "rebound height, mm", "sd", "n", "status"}, {}, {}};
  std::vector<std::vector<double>> rows;
  for (const auto& r : member(j, "rows")) {
    const auto& c = member(r, "contact_points");
    const auto& h = member(r, "rebound_height_m");
    std::string status = r.value("status", std::string("ok"));
    if (r.contains("failure")) status += ": " + format_value(member(r["failure"], "message"));
    t.add_row({format_value(r.value("youngs_modulus_pa", nlohmann::json())), format_value(c.value("mean", nlohmann::json())),
               format_value(c.value("sd", nlohmann::json())), mm(h.value("mean", nlohmann::json())), mm(h.value("sd", nlohmann::json())),
               format_value(h.value("n", nlohmann::json())), status});
    rows.push_back({as_number(r.value("youngs_modulus_pa", nlohmann::json())), as_number(c.value("mean", nlohmann::json())),
                    as_number(c.value("sd", nlohmann::json())), 1000.0 * as_number(h.value("mean", nlohmann::json())),
                    1000.0 * as_number(h.value("sd", nlohmann::json()))});
  }
  t.notes.push_back("Contact points fall as E rises: " + format_value(j.value("contact_points_fall_with_E", nlohmann::json())) +
                    "; rebound rises as E rises: " + format_value(j.value("rebound_rises_with_E", nlohmann::json())) +
                    " (over the moduli whose drops completed).");
  s.table(std::move(t));
  GnuplotPlot p;
  p.add_data("rows.dat", rows);
  p.script = "set title 'Free drop under HMNR against Young''s modulus'\nset logscale x\nset xlabel 'Young''s modulus (Pa)'\n"
             "set ylabel 'contact points at impact'\nset y2label 'rebound height (mm)'\nset ytics nomirror\nset y2tics\nset grid\n"
             "set offsets graph 0.1, graph 0.1, graph 0.1, graph 0.1\nset key outside right top vertical\n"
             "plot 'rows.dat' using 1:2:3 with yerrorlines pt 7 lc rgb '#1f77b4' title 'contact points', "
             "'rows.dat' using 1:4:5 axes x1y2 with yerrorlines pt 5 lc rgb '#d62728' title 'rebound height'\n";
  if (!rows.empty()) add_plot(s, "stiffness", "Contact points and rebound height against Young's modulus (mean and sd)", p);
  doc.sections.push_back(std::move(s));
}

// Speed against accuracy: one scene's index per setting, its change and its cost.
void add_tradeoff(const nlohmann::json& j, Document& doc) {
  Section s{"tradeoff", "Speed against accuracy", {}};
  const double tol = as_number(j.value("tolerance", nlohmann::json()));
  s.paragraph("Scene " + format_value(j.value("scene", nlohmann::json(""))) + " (overrides " + format_value(j.value("sets", nlohmann::json::array())) +
              "), index " + format_value(j.value("metric", nlohmann::json(""))) + ", " + format_value(j.value("repeats", nlohmann::json())) +
              " seeds per row, the same in every row; tolerance " + format_percent(j.value("tolerance", nlohmann::json())) + ".");
  std::string data;
  int sweep = 0;
  for (const auto& sw : member(j, "sweeps")) {
    const std::string param = sw.value("parameter", std::string("?"));
    Table t{"tradeoff_" + file_stem(param), "Sweep of " + param,
            {"value", "index mean", "sd", "n", "change", "beyond 2 se", "CPU s per run", "steps per run", "seeds", "spheres", "speed-up", "within tolerance", "status"}, {}, {}};
    for (const auto& r : member(sw, "rows")) {
      const auto& ix = member(r, "index");
      std::string status = r.value("status", std::string("ok"));
      if (r.contains("same_runs_as")) status += " (the runs of " + format_value(r["same_runs_as"]) + ")";
      if (r.contains("failure")) status += ": " + format_value(member(r["failure"], "message"));
      t.add_row({format_value(r.value("value", nlohmann::json())), format_value(ix.value("mean", nlohmann::json())), format_value(ix.value("sd", nlohmann::json())),
                 format_value(ix.value("n", nlohmann::json())), format_percent(r.value("relative_change", nlohmann::json())),
                 format_value(r.value("significant", nlohmann::json())), format_value(r.value("cpu_seconds_per_run", nlohmann::json())),
                 format_value(r.value("steps_per_run", nlohmann::json())), format_value(r.value("seeds_per_run", nlohmann::json())),
                 format_value(r.value("spheres_per_run", nlohmann::json())), format_value(r.value("speedup", nlohmann::json())),
                 format_value(r.value("within_tolerance", nlohmann::json())), status});
      const double x = as_number(r.value("speedup", nlohmann::json())), y = 100.0 * as_number(r.value("relative_change", nlohmann::json()));
      // Every sweep's reference sits at (1, 0): only the first is labelled, as "reference".
      const bool reference = r.value("value", nlohmann::json()) == sw.value("reference", nlohmann::json());
      const std::string label = reference ? (sweep == 0 ? "reference" : "") : format_value(r["value"]);
      if (std::isfinite(x) && std::isfinite(y))
        data += std::to_string(sweep) + " " + gp_number(x) + " " + gp_number(y) + " " + gp_data_string(label) + "\n";
    }
    t.notes.push_back("Reference: " + format_value(sw.value("reference", nlohmann::json())) + "; cheapest within the tolerance: " +
                      format_value(sw.value("cheapest_within_tolerance", nlohmann::json())) + ".");
    s.table(std::move(t));
    ++sweep;
  }
  if (!data.empty()) {
    GnuplotPlot p;
    p.data = {{"rows.dat", data}};
    const std::string band = std::isfinite(tol) ? gp_number(100.0 * tol) : "0";
    p.script = "set title 'Change of the index against the speed-up'\nset logscale x\nset xlabel 'speed-up against the reference row'\n"
               "set ylabel 'change of the index (%)'\nset grid\nset key outside right top vertical\n"
               "set offsets graph 0.1, graph 0.15, graph 0.15, graph 0.15\n"
               "plot " + band + " with lines dt 2 lc rgb '#888888' title 'tolerance', -" + band + " with lines dt 2 lc rgb '#888888' notitle, "
               "'rows.dat' using ($1 == 0 ? $2 : 1/0):3 with linespoints pt 7 lc rgb '#1f77b4' title 'time-step fraction', "
               "'rows.dat' using ($1 == 1 ? $2 : 1/0):3 with linespoints pt 5 lc rgb '#d62728' title 'Young''s modulus', "
               "'rows.dat' using 2:3:4 with labels offset 0,1 notitle\n";
    add_plot(s, "tradeoff", "Index change against speed-up, one point per setting (refused settings have none)", p);
  }
  doc.sections.push_back(std::move(s));
}

// An index against one setting: every level's mean and sd, every step in pooled sd, the verdict.
void add_trend(const nlohmann::json& j, Document& doc) {
  const std::string key = j.value("key", std::string("?"));
  Section s{"trend", "Trend check: " + format_value(j.value("metric", nlohmann::json(""))) + " against " + key, {}};
  s.paragraph("Scene " + format_value(j.value("scene", nlohmann::json(""))) + " (overrides " + format_value(j.value("sets", nlohmann::json::array())) +
              "), " + format_value(j.value("repeats", nlohmann::json())) + " seeds per level, the same at every level; expected to " +
              format_value(j.value("expect", nlohmann::json(""))) + " by more than " + format_value(j.value("sd_multiple", nlohmann::json())) +
              " pooled sd. " + format_value(j.value("verdict", nlohmann::json(""))) + ".");
  Table t{"trend_levels", "Levels", {key, "index mean", "sd", "n", "CPU s per run", "status"}, {}, {}};
  std::vector<std::vector<double>> rows;
  for (const auto& l : member(j, "levels")) {
    const auto& ix = member(l, "index");
    std::string status = l.value("status", std::string("ok"));
    if (l.contains("failure")) status += ": " + format_value(member(l["failure"], "message"));
    t.add_row({format_value(l.value("value", nlohmann::json())), format_value(ix.value("mean", nlohmann::json())),
               format_value(ix.value("sd", nlohmann::json())), format_value(ix.value("n", nlohmann::json())),
               format_value(l.value("cpu_seconds_per_run", nlohmann::json())), status});
    for (const auto& x : ix.value("samples", nlohmann::json::array()))
      rows.push_back({as_number(l.value("value", nlohmann::json())), as_number(x)});
  }
  s.table(std::move(t));
  Table c{"trend_steps", "Steps between levels", {"from", "to", "difference", "pooled sd", "difference / pooled sd", "expected way", "beyond required"}, {}, {}};
  auto add = [&](const nlohmann::json& st) {
    c.add_row({format_value(st.value("from", nlohmann::json())), format_value(st.value("to", nlohmann::json())),
               format_value(st.value("difference", nlohmann::json())), format_value(st.value("pooled_sd", nlohmann::json())),
               format_value(st.value("difference_in_pooled_sd", nlohmann::json())), format_value(st.value("expected_direction", nlohmann::json())),
               format_value(st.value("beyond_required_sd", nlohmann::json()))});
  };
  for (const auto& st : member(j, "steps")) add(st);
  add(member(j, "overall"));
  c.notes.push_back("The last row compares the first and the last level; confirmed: " + format_value(j.value("confirmed", nlohmann::json())) + ".");
  s.table(std::move(c));
  if (!rows.empty()) {
    GnuplotPlot p;
    p.add_data("samples.dat", rows);
    p.script = "set title " + gp_quote("Every run against " + key) + "\nset xlabel " + gp_quote(key) + "\nset ylabel " +
               gp_quote(j.value("metric", std::string("index"))) + "\nset grid\nset offsets graph 0.1, graph 0.1, graph 0.1, graph 0.1\n"
               "plot 'samples.dat' using 1:2 with points pt 7 lc rgb '#1f77b4' title 'runs', "
               "'samples.dat' using 1:2 smooth unique with lines lc rgb '#d62728' title 'mean'\n";
    add_plot(s, "trend", "Index of every run against " + key + ", with the level means", p);
  }
  doc.sections.push_back(std::move(s));
}

// Young's modulus against moisture, and the dimensions after soaking (no DEM).
void add_moisture(const nlohmann::json& j, Document& doc) {
  Section s{"moisture", "Moisture study: " + format_value(j.value("variety", nlohmann::json(""))), {}};
  const auto& f = member(j, "log_linear_fit");
  s.paragraph("ln E = " + format_value(f.value("c0", nlohmann::json())) + " + " + format_value(f.value("c1", nlohmann::json())) +
              " w (R2 " + format_value(f.value("r2", nlohmann::json())) + ", slope p " + format_value(f.value("p_c1", nlohmann::json())) +
              ", n " + format_value(f.value("n", nlohmann::json())) + "); E at the variety's moisture " +
              format_value(j.value("youngs_modulus_at_variety_moisture_pa", nlohmann::json())) + " Pa.");
  Table t{"moisture_soaking", "Dimensions after soaking", {"hours", "L before, mm", "W before, mm", "T before, mm", "L after, mm", "W after, mm",
                                                          "T after, mm", "volume growth"}, {}, {}};
  for (const auto& r : member(j, "rows")) {
    const auto& b = member(r, "before_m");
    const auto& a = member(r, "after_m");
    if (!b.is_array() || !a.is_array() || b.size() < 3 || a.size() < 3) continue;
    t.add_row({format_value(r.value("hours", nlohmann::json())), mm(b[0]), mm(b[1]), mm(b[2]), mm(a[0]), mm(a[1]), mm(a[2]),
               format_value(r.value("volume_growth_ratio", nlohmann::json()))});
  }
  s.table(std::move(t));
  doc.sections.push_back(std::move(s));
}

}  // namespace

std::vector<std::string> study_outputs(const std::string& dir) {
  std::vector<std::string> out;
  for (const auto& k : kKinds)
    if (std::filesystem::exists(dir + "/" + k + ".json")) out.push_back(k);
  return out;
}

Document build_studies_report(const std::string& dir) {
  const auto kinds = study_outputs(dir);
  if (kinds.empty())
    throw InputError(dir + ": no multicontact.json, stiffness.json, tradeoff.json, trend.json or moisture.json here (give the --out "
                     "directory of `seedcal study`)");
  Document doc;
  doc.title = "Study report";
  doc.subtitle.push_back("Directory " + dir + "; rendered by seedcal " + version_string());
  for (const auto& k : kinds) {
    const auto j = read_json(dir + "/" + k + ".json");
    if (j.contains("provenance")) doc.subtitle.push_back(k + ": " + j["provenance"].dump());
    if (k == "multicontact") add_multicontact(j, doc);
    if (k == "stiffness") add_stiffness(j, doc);
    if (k == "tradeoff") add_tradeoff(j, doc);
    if (k == "trend") add_trend(j, doc);
    if (k == "moisture") add_moisture(j, doc);
  }
  make_ids_unique(doc);
  return doc;
}

std::vector<std::string> render_studies_report(const std::string& dir) {
  return write_report(build_studies_report(dir), dir);
}

}  // namespace seedcal::reports
