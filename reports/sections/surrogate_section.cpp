// The response-surface design with its responses, and the surrogates fitted to every run on the
// kept subspace: fit statistics per solve round (quadratic R2, adjusted and predicted R2 and
// leave-one-out RMSE; the Gaussian process's noise and leave-one-out RMSE; which one was chosen
// and why), the ANOVA table and coefficients of the last round's quadratic fit.
#include "reports/sections/common.hpp"
#include "reports/sections/sections.hpp"

namespace seedcal::reports {
namespace {

// R-style significance code of a p-value.
std::string significance(const nlohmann::json& p) {
  if (!p.is_number()) return "";
  const double v = p.get<double>();
  return v < 0.001 ? "***" : v < 0.01 ? "**" : v < 0.05 ? "*" : v < 0.1 ? "." : "";
}

void add_design(const StudyData& d, Document& doc) {
  const auto* sd = d.stage("surrogate_design");
  if (!sd) return;
  Section s{"surface-design", "Response-surface design", {}};
  const auto factors = kept_factors(d);
  auto names = strings_of(sd->value("targets", nlohmann::json::array()));
  if (names.empty()) names = target_names(d);
  s.paragraph(sd->value("design", std::string("design")) + ", " + format_value(sd->value("runs", nlohmann::json())) + " runs x " +
              format_value(sd->value("replicates", nlohmann::json(1))) +
              " replicate(s) in the surrogate box; responses are means over the replicates that finished.");
  const auto& coded = sd->value("coded", nlohmann::json::array());
  const auto& natural = sd->value("natural", nlohmann::json::array());
  const auto& responses = sd->value("responses", nlohmann::json::array());
  Table t{"surface_design", "Response-surface runs", {"run"}, {}, {}};
  if (!coded.empty())
    for (const auto& f : factors) t.columns.push_back(f + " (coded)");
  for (const auto& f : factors) t.columns.push_back(f);
  for (std::size_t r = 0; r < responses.size(); ++r) t.columns.push_back(r < names.size() ? names[r] : std::string("response ") + std::to_string(r + 1));
  for (std::size_t i = 0; i < natural.size(); ++i) {
    std::vector<std::string> row{std::to_string(i + 1)};
    if (!coded.empty())
      for (std::size_t j = 0; j < factors.size(); ++j) row.push_back(i < coded.size() && j < coded[i].size() ? format_value(coded[i][j]) : "n/a");
    for (std::size_t j = 0; j < factors.size(); ++j) row.push_back(j < natural[i].size() ? format_value(natural[i][j]) : "n/a");
    for (const auto& col : responses) row.push_back(i < col.size() ? format_value(col[i]) : "n/a");
    t.add_row(std::move(row));
  }
  if (coded.empty()) t.notes.push_back(needs_newer_store("the coded settings"));
  s.table(std::move(t));
  doc.sections.push_back(std::move(s));
}

void add_fit(const StudyData& d, Document& doc) {
  const int last = d.last_solve_round();
  if (last == 0) return;
  Section s{"surrogate-fit", "Surrogate fit: ANOVA and fit statistics", {}};
  Table stats{"fit_statistics", "Fit statistics per solve round (leave-one-out RMSE in response units)",
              {"round", "target", "points", "R2", "adj R2", "pred R2", "quadratic sigma", "quadratic LOO RMSE", "GP noise sd",
               "GP noise floor sd", "GP signal sd", "GP LOO RMSE", "chosen", "rule"}, {}, {}};
  for (int r = 1; r <= last; ++r) {
    const auto* st = d.stage(std::string("solve_round_") + std::to_string(r));
    if (!st) continue;
    for (const auto& t : st->value("targets", nlohmann::json::array())) {
      const auto q = t.value("quadratic", nlohmann::json::object()), g = t.value("gp", nlohmann::json::object());
      auto get = [](const nlohmann::json& o, const char* k) { return format_value(o.value(k, nlohmann::json())); };
      stats.add_row({std::to_string(r), t.value("name", std::string("?")), get(t, "points"), get(q, "r2"), get(q, "adj_r2"),
                     get(q, "pred_r2"), get(q, "sigma"), get(q, "loo_rmse"), get(g, "noise_sd"), get(g, "noise_floor_sd"), get(g, "signal_sd"),
                     get(g, "loo_rmse"), t.value("chosen", std::string("n/a")), t.value("choice_rule", std::string("n/a"))});
    }
  }
  stats.notes.push_back("pred R2 = 1 - PRESS / SS_total; the quadratic's LOO RMSE is sqrt(PRESS / n) (Allen 1974), the "
                        "Gaussian process's from R&W eq. 5.12; with the rule \"smaller leave-one-out RMSE\" the surrogate "
                        "with the smaller one is used to solve for the target. The GP noise floor is the lower 95 % bound of the "
                        "run-to-run noise the screening measured (none for a deterministic scene).");
  const auto* st = d.stage(std::string("solve_round_") + std::to_string(last));
  const auto& targets = st->value("targets", nlohmann::json::array());
  const auto names = target_names(d);
  for (std::size_t ti = 0; ti < targets.size(); ++ti) {
    const auto& t = targets[ti];
    const std::string name = t.value("name", std::string("?"));
    const auto q = t.value("quadratic", nlohmann::json::object()), g = t.value("gp", nlohmann::json::object());
    std::string why = std::string("Round ") + std::to_string(last) + ", " + name + ": " + format_value(t.value("points", nlohmann::json())) +
                      " runs; the " + (t.value("chosen", std::string()) == "gp" ? "Gaussian process" : "quadratic model") +
                      " was chosen (" + t.value("choice_rule", std::string("n/a")) + ": quadratic " +
                      format_value(q.value("loo_rmse", nlohmann::json())) + ", Gaussian process " +
                      format_value(g.value("loo_rmse", nlohmann::json())) + ").";
    if (q.contains("error")) why += " The quadratic could not be fitted: " + q["error"].get<std::string>() + ".";
    if (g.contains("error")) why += " The Gaussian process could not be fitted: " + g["error"].get<std::string>() + ".";
    if (g.contains("length_scales_coded"))
      why += " GP kernel " + g.value("kernel", std::string("?")) + ", length scales (coded) " + format_value(g["length_scales_coded"]) + ".";
    s.paragraph(why);
    const std::string suffix = target_suffix(names, ti);
    if (q.contains("anova")) {
      Table a{"anova" + suffix, "ANOVA of the quadratic fit to " + name + " (round " + std::to_string(last) + ", sequential sums of squares)",
              {"source", "SS", "df", "MS", "F", "p", "significance"}, {}, {}};
      for (const auto& row : q["anova"])
        a.add_row({row.value("source", std::string("?")), format_value(row.value("ss", nlohmann::json())),
                   format_value(row.value("df", nlohmann::json())), format_value(row.value("ms", nlohmann::json())),
                   format_value(row.value("f", nlohmann::json())), format_value(row.value("p", nlohmann::json())),
                   significance(row.value("p", nlohmann::json()))});
      a.notes.push_back("Significance codes: *** p < 0.001, ** p < 0.01, * p < 0.05, . p < 0.1. R2 " + format_value(q.value("r2", nlohmann::json())) +
                        ", adjusted R2 " + format_value(q.value("adj_r2", nlohmann::json())) + ", predicted R2 " +
                        format_value(q.value("pred_r2", nlohmann::json())) + ", adequate precision " +
                        format_value(q.value("adequate_precision", nlohmann::json())) + ".");
      s.table(std::move(a));
    } else if (!q.empty() && !q.contains("error")) {
      s.note(needs_newer_store("the ANOVA table of " + name));
    }
    if (q.contains("coefficients")) {
      Table c{"coefficients" + suffix, "Quadratic model of " + name + " in box-coded units (-1 .. 1 per factor)",
              {"term", "estimate", "standard error", "t", "p"}, {}, {}};
      for (const auto& row : q["coefficients"])
        c.add_row({row.value("term", std::string("?")), format_value(row.value("estimate", nlohmann::json())),
                   format_value(row.value("se", nlohmann::json())), format_value(row.value("t", nlohmann::json())),
                   format_value(row.value("p", nlohmann::json()))});
      s.table(std::move(c));
    } else if (q.contains("coefficients_coded")) {
      Table c{"coefficients" + suffix, "Quadratic model of " + name + " in box-coded units (-1 .. 1 per factor)", {"term", "estimate"}, {}, {}};
      for (const auto& [term, v] : q["coefficients_coded"].items()) c.add_row({term, format_value(v)});
      s.table(std::move(c));
    }
  }
  s.table(std::move(stats));
  doc.sections.push_back(std::move(s));
}

}  // namespace

void add_surrogate_sections(const StudyData& d, Document& doc) {
  add_design(d, doc);
  add_fit(d, doc);
}

}  // namespace seedcal::reports
