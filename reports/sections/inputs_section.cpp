// Study inputs: provenance (study file, seed, version, fingerprint), the parameters with their
// ranges and the targets as the study file gives them (read back from the store's copy of the
// file, so the report needs nothing but the study directory), the tolerance, and the file itself.
#include <cmath>
#include <limits>
#include <sstream>

#include <toml.hpp>

#include "reports/sections/common.hpp"
#include "reports/sections/sections.hpp"

namespace seedcal::reports {
namespace {

std::string toml_text(const toml::value& v) {
  if (v.is_floating()) return format_number(v.as_floating());
  if (v.is_integer()) return std::to_string(v.as_integer());
  if (v.is_boolean()) return v.as_boolean() ? "yes" : "no";
  if (v.is_string()) return v.as_string().str;
  if (v.is_array()) {
    std::string out;
    for (const auto& x : v.as_array()) out += std::string(out.empty() ? "" : ", ") + toml_text(x);
    return out;
  }
  return toml::format(v);
}

std::string field(const toml::value& table, const std::string& key, const std::string& absent) {
  return table.is_table() && table.contains(key) ? toml_text(table.at(key)) : absent;
}

// The parameters and targets tables from the study file's text (as stored); false when the text
// does not parse.
bool add_study_tables(const std::string& text, const StudyData& d, Section& s) {
  toml::value doc;
  try {
    std::istringstream in(text);
    doc = toml::parse(in, "study file");
  } catch (const std::exception&) {
    return false;
  }
  const auto kept = d.stage("screen") ? strings_of((*d.stage("screen"))["kept"]) : std::vector<std::string>{};
  if (doc.contains("parameter") && doc.at("parameter").is_array()) {
    Table t{"parameters", "Parameters (screening range low .. high, hard limits min .. max; blank fields take "
                          "the defaults of docs/calibrate.md)",
            {"parameter", "calibrate", "low", "high", "min", "max", "nominal", "prior", "kept after screening"}, {}, {}};
    for (const auto& p : doc.at("parameter").as_array()) {
      const std::string path = field(p, "path", "?");
      const bool is_kept = std::find(kept.begin(), kept.end(), path) != kept.end();
      t.add_row({path, field(p, "calibrate", "no"), field(p, "low", ""), field(p, "high", ""), field(p, "min", ""),
                 field(p, "max", ""), field(p, "nominal", ""), field(p, "prior", ""),
                 d.stage("screen") ? (is_kept ? "yes" : "no") : "n/a"});
    }
    s.table(std::move(t));
  }
  if (doc.contains("target") && doc.at("target").is_array()) {
    Table t{"targets", "Targets (measured values the study fits)", {"name", "metric", "value", "weight", "scene", "scene settings"}, {}, {}};
    for (const auto& x : doc.at("target").as_array())
      t.add_row({field(x, "name", field(x, "metric", "?")), field(x, "metric", "?"), field(x, "value", "n/a"),
                 field(x, "weight", "1"), field(x, "scene", ""), field(x, "set", "")});
    s.table(std::move(t));
  }
  return true;
}

}  // namespace

void add_inputs_section(const StudyData& d, Document& doc) {
  Section s{"inputs", "Study inputs", {}};
  const SummaryProvenance prov = d.summary ? d.summary->provenance : SummaryProvenance{};
  Table t{"study", "Study", {"item", "value"}, {}, {}};
  auto row = [&t](const std::string& k, const std::string& v) {
    if (!v.empty()) t.add_row({k, v});
  };
  row("study", d.summary ? d.summary->study : std::string());
  row("study file", prov.study_file);
  if (d.summary) row("seed", std::to_string(prov.seed));
  row("seedcal version (store)", d.header.seedcal_version);
  row("seedcal version (summary)", prov.seedcal_version);
  row("config hash", d.has_store ? d.header.config_hash : prov.config_hash);
  row("store created (UTC)", d.header.created_utc);
  const auto* confirm = d.stage("confirm");
  const double tol = d.summary && std::isfinite(d.summary->tolerance) ? d.summary->tolerance : confirm ? as_number(member(*confirm, "tolerance")) : std::numeric_limits<double>::quiet_NaN();
  if (std::isfinite(tol)) row("tolerance (relative error)", format_number(100.0 * tol) + " %");
  if (confirm && confirm->contains("budget")) row("budget of DEM runs", format_value((*confirm)["budget"]));
  if (const auto* screen = d.stage("screen"); screen && screen->contains("alpha"))
    row("screening significance level", format_value((*screen)["alpha"]));
  if (!t.rows.empty()) s.table(std::move(t));

  const std::string text = d.has_store ? d.header.config_text : prov.config;
  if (!text.empty()) {
    if (!add_study_tables(text, d, s)) s.note("The stored study file text could not be parsed: parameters and targets are shown in the file below only");
    s.preformatted("Study file (as stored, after --set overrides)", text);
  } else {
    s.note("Neither the store nor summary.json holds the study file's text");
  }
  for (const auto& p : d.problems) s.note(p);
  doc.sections.push_back(std::move(s));
}

}  // namespace seedcal::reports
