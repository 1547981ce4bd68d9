// Screening: the Plackett-Burman design with its responses, and per target the effects table
// (effect, standard error, t, p, significance at the study's alpha) with a Pareto chart of |t|
// and the two-sided critical t_{1-alpha/2, df} (Student t, GSL) as the significance threshold.
#include <algorithm>
#include <cmath>

#include <gsl/gsl_cdf.h>

#include "reports/sections/common.hpp"
#include "reports/sections/sections.hpp"

namespace seedcal::reports {
namespace {

void add_design(const nlohmann::json& sc, Document& doc) {
  Section s{"screening-design", "Screening design and responses", {}};
  const auto factors = strings_of(sc["factors"]);
  const int dummies = sc.value("dummy_columns", 0);
  s.paragraph(sc.value("design", std::string("Plackett-Burman")) + " design, " + format_value(sc.value("runs", nlohmann::json())) +
              " runs x " + format_value(sc.value("replicates", nlohmann::json(1))) + " replicate(s), " +
              std::to_string(factors.size()) + " factors and " + std::to_string(dummies) +
              " dummy columns (used to estimate the error). Responses are means over the replicates that finished.");
  Table t{"screening_design", "Screening runs: natural factor settings, coded signs (factors then dummy columns) and responses",
          {"run", "signs"}, {}, {}};
  for (const auto& f : factors) t.columns.push_back(f);
  const auto& targets = sc.value("targets", nlohmann::json::array());
  for (const auto& tg : targets) t.columns.push_back(tg.value("name", std::string("response")) + " (" + tg.value("metric", std::string()) + ")");
  const auto& coded = sc.value("coded", nlohmann::json::array());
  const auto& natural = sc.value("natural", nlohmann::json::array());
  for (std::size_t i = 0; i < natural.size(); ++i) {
    std::vector<std::string> row{std::to_string(i + 1), ""};
    if (i < coded.size())
      for (const auto& c : coded[i]) row[1] += as_number(c) > 0 ? '+' : '-';
    for (std::size_t j = 0; j < factors.size(); ++j) row.push_back(j < natural[i].size() ? format_value(natural[i][j]) : "n/a");
    for (const auto& tg : targets) {
      const auto& r = tg.value("responses", nlohmann::json::array());
      row.push_back(i < r.size() ? format_value(r[i]) : "n/a");
    }
    t.add_row(std::move(row));
  }
  s.table(std::move(t));
  doc.sections.push_back(std::move(s));
}

void add_effects(const nlohmann::json& sc, Document& doc) {
  Section s{"effects", "Effects and their significance", {}};
  const double alpha = sc.value("alpha", 0.05);
  const auto kept = strings_of(sc.value("kept", nlohmann::json::array()));
  const auto& targets = sc.value("targets", nlohmann::json::array());
  std::vector<std::string> names;
  for (const auto& tg : targets) names.push_back(tg.value("name", std::string("target")));
  for (std::size_t ti = 0; ti < targets.size(); ++ti) {
    const auto& tg = targets[ti];
    const std::string name = names[ti], suffix = target_suffix(names, ti);
    if (!tg.contains("effects")) {
      s.note(name + ": " + tg.value("analysis", std::string("no effects analysis")));
      continue;
    }
    const int df = tg.value("df_error", 0);
    const double t_crit = df > 0 ? gsl_cdf_tdist_Pinv(1.0 - 0.5 * alpha, static_cast<double>(df)) : NAN;
    Table t{"effects" + suffix, "Effects on " + name + " (effect = mean at + minus mean at -)",
            {"factor", "effect", "standard error", "t", "p", "significant (alpha " + format_number(alpha) + ")", "kept"}, {}, {}};
    t.notes.push_back("Error estimate: " + tg.value("error_source", std::string("n/a")) + ", " + std::to_string(df) +
                      " degrees of freedom; critical |t| = " + format_number(t_crit, 4) +
                      ". Kept: the parameters the study calibrates plus every significant one.");
    struct Bar { std::string factor; double t, effect; bool significant; };
    std::vector<Bar> bars;
    for (const auto& e : tg["effects"]) {
      const std::string f = e.value("factor", std::string("?"));
      const bool sig = e.value("significant", false), is_kept = std::find(kept.begin(), kept.end(), f) != kept.end();
      t.add_row({f, format_value(e.value("effect", nlohmann::json())), format_value(e.value("se", nlohmann::json())),
                 format_value(e.value("t", nlohmann::json())), format_value(e.value("p", nlohmann::json())), sig ? "yes" : "no",
                 is_kept ? "yes" : "no"});
      bars.push_back({f, std::fabs(as_number(e.value("t", nlohmann::json()))), std::fabs(as_number(e.value("effect", nlohmann::json()))), sig});
    }
    s.table(std::move(t));

    // Pareto chart: horizontal bars sorted by size, the largest on top.
    const bool by_t = std::all_of(bars.begin(), bars.end(), [](const Bar& b) { return std::isfinite(b.t); }) && std::isfinite(t_crit);
    std::sort(bars.begin(), bars.end(), [by_t](const Bar& a, const Bar& b) { return by_t ? a.t < b.t : a.effect < b.effect; });
    GnuplotPlot p;
    p.width = 860;
    p.height = std::max(260, 80 + 34 * static_cast<int>(bars.size()));
    std::string rows, labels;
    std::vector<std::string> label_list;
    double top = 0.0;
    for (std::size_t i = 0; i < bars.size(); ++i) {
      const double v = by_t ? bars[i].t : bars[i].effect;
      if (!std::isfinite(v)) continue;
      top = std::max(top, v);
      rows += std::to_string(i) + " " + gp_number(v) + " " + std::string(bars[i].significant ? "1" : "0") + " " + gp_data_string(bars[i].factor) + "\n";
      label_list.push_back(bars[i].factor);
    }
    if (rows.empty()) continue;
    p.data.emplace_back("bars.dat", rows);
    if (by_t) top = std::max(top, t_crit);
    p.script = "set title " + gp_quote("Pareto chart of effects on " + name) + "\nset lmargin " +
               std::to_string(label_margin(label_list)) + "\nset xlabel " + gp_quote(by_t ? "|t| of the effect" : "|effect|") +
               "\nset xrange [0:" + gp_number(1.1 * top) + "]\nset yrange [-0.6:" + gp_number(static_cast<double>(bars.size()) - 0.4) +
               "]\nset grid xtics\nset key outside right top vertical\nset style fill solid 0.8 border rgb '#333333'\n";
    if (by_t)
      p.script += "set arrow 1 from " + gp_number(t_crit) + ", graph 0 to " + gp_number(t_crit) +
                  ", graph 1 nohead lw 2 dt 2 lc rgb '#d62728'\n";
    p.script += "plot 'bars.dat' using (0):1:(0):2:($1-0.35):($1+0.35):($3 > 0 ? 0x1f77b4 : 0xaaaaaa):ytic(4) "
                "with boxxyerror lc rgb variable notitle";
    if (by_t)
      p.script += ", NaN with lines lw 2 dt 2 lc rgb '#d62728' title " +
                  gp_quote("critical |t| = " + format_number(t_crit, 4) + " (alpha " + format_number(alpha) + ")") +
                  ", NaN with boxes lc rgb '#1f77b4' title 'significant', NaN with boxes lc rgb '#aaaaaa' title 'not significant'";
    p.script += "\n";
    add_plot(s, "effects_pareto" + suffix,
             "Pareto chart of the screening effects on " + name +
                 (by_t ? " (|t|; dashed line: significance threshold)" : " (|effect|; no error estimate, so no threshold)"),
             p);
  }
  doc.sections.push_back(std::move(s));
}

}  // namespace

void add_screening_sections(const StudyData& d, Document& doc) {
  const auto* sc = d.stage("screen");
  if (!sc) return;
  add_design(*sc, doc);
  add_effects(*sc, doc);
}

}  // namespace seedcal::reports
