#include "reports/report.hpp"

#include <filesystem>
#include <set>

#include "reports/html_writer.hpp"
#include "reports/markdown_writer.hpp"
#include "reports/sections/sections.hpp"
#include "store/atomic_file.hpp"
#include "store/version.hpp"

namespace seedcal::reports {

Document build_report(const StudyData& study) {
  Document doc;
  const std::string name = study.summary ? study.summary->study : std::string();
  doc.title = "Calibration report" + (name.empty() ? std::string() : ": " + name);
  if (study.summary && !study.summary->provenance.study_file.empty())
    doc.subtitle.push_back("Study file " + study.summary->provenance.study_file);
  doc.subtitle.push_back("Study directory " + study.dir + "; rendered by seedcal " + version_string());
  add_answer_section(study, doc);
  add_inputs_section(study, doc);
  add_screening_sections(study, doc);
  add_ascent_section(study, doc);
  add_surrogate_sections(study, doc);
  add_surface_plot_sections(study, doc);
  add_confirmation_section(study, doc);
  add_posterior_plot_section(study, doc);
  add_curve_section(study, doc);
  add_summary_section(study, doc);
  add_verification_sections(study, doc);
  add_scenes_section(study, doc);
  make_ids_unique(doc);
  return doc;
}

void make_ids_unique(Document& doc) {
  std::set<std::string> tables, plots;
  auto unique = [](std::set<std::string>& seen, std::string& id) {
    const std::string base = id;
    for (int k = 2; !seen.insert(id).second; ++k) id = base + "_" + std::to_string(k);
  };
  for (auto& s : doc.sections)
    for (auto& b : s.blocks) {
      if (auto* t = std::get_if<Table>(&b)) unique(tables, t->id);
      if (auto* p = std::get_if<Plot>(&b)) unique(plots, p->id);
    }
}

std::vector<std::string> write_report(const Document& doc, const std::string& dir) {
  namespace fs = std::filesystem;
  const fs::path out = fs::path(dir) / "report";
  fs::create_directories(out);
  std::vector<std::string> written;
  std::set<std::string> keep;
  auto write = [&](const fs::path& p, const std::string& text) {
    write_file_atomic(p.string(), text);
    written.push_back(p.string());
  };
  for (const auto& s : doc.sections)
    for (const auto& b : s.blocks) {
      if (const auto* t = std::get_if<Table>(&b)) {
        write(out / (t->id + ".csv"), to_csv(*t));
        keep.insert(t->id + ".csv");
      }
      if (const auto* p = std::get_if<Plot>(&b); p && p->written) {
        write(out / (p->id + ".svg"), p->svg);
        keep.insert(p->id + ".svg");
      }
    }
  // What an earlier rendering wrote and this one does not (a section the study no longer has).
  for (const auto& e : fs::directory_iterator(out)) {
    const std::string f = e.path().filename().string(), ext = e.path().extension().string();
    if (e.is_regular_file() && (ext == ".csv" || ext == ".svg") && !keep.count(f)) fs::remove(e.path());
  }
  write(fs::path(dir) / "report.html", render_html(doc));
  write(fs::path(dir) / "report.md", render_markdown(doc));
  return written;
}

std::vector<std::string> render_report(const std::string& dir) {
  return write_report(build_report(load_study(dir)), dir);
}

}  // namespace seedcal::reports
