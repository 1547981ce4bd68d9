// Pictures of the scenes: every SVG under DIR/scenes/ (side views with fitted lines; the
// verification stage writes DIR/scenes/MODEL/TEST/) embedded as it is, and every
// direct_shear_curve.csv there
// (columns displacement_m, shear_stress_pa, smoothed_shear_stress_pa, normal_stress_pa,
// lid_height_m; calibrate/scenes/direct_shear_scene.cpp) plotted as shear stress against
// displacement.
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "reports/sections/common.hpp"
#include "reports/sections/sections.hpp"

namespace seedcal::reports {
namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// The shear curve's rows (displacement mm, stress kPa, smoothed kPa); empty when the header is not
// the one the direct-shear scene writes.
std::vector<std::vector<double>> shear_rows(const std::string& csv) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  if (line.rfind("displacement_m,shear_stress_pa,smoothed_shear_stress_pa", 0) != 0) return {};
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::istringstream cells(line);
    std::string cell;
    std::vector<double> v;
    while (std::getline(cells, cell, ',') && v.size() < 3) {
      try {
        v.push_back(std::stod(cell));
      } catch (const std::exception&) {
        v.push_back(NAN);
      }
    }
    if (v.size() == 3) rows.push_back({1e3 * v[0], 1e-3 * v[1], 1e-3 * v[2]});
  }
  return rows;
}

}  // namespace

void add_scenes_section(const StudyData& d, Document& doc) {
  const fs::path root = fs::path(d.dir) / "scenes";
  std::error_code ec;
  if (!fs::is_directory(root, ec)) return;
  std::vector<fs::path> files;  // depth-first, sorted: one scene's files together
  for (auto it = fs::recursive_directory_iterator(root, fs::directory_options::skip_permission_denied, ec);
       !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (it.depth() > 4) it.disable_recursion_pending();
    if (it->is_regular_file(ec) && (it->path().extension() == ".svg" || it->path().filename() == "direct_shear_curve.csv"))
      files.push_back(it->path());
  }
  std::sort(files.begin(), files.end());
  Section s{"scenes", "Scenes", {}};
  for (const auto& f : files) {
    const std::string rel = fs::relative(f, d.dir, ec).generic_string();
    const std::string name = fs::relative(f.parent_path(), root, ec).generic_string();  // MODEL/TEST
    if (f.extension() == ".svg") {
      const std::string svg = read_text(f);
      const std::string l = lower(svg);
      if (svg.find("<svg") == std::string::npos || l.find("<script") != std::string::npos ||
          l.find("javascript:") != std::string::npos || l.find("<foreignobject") != std::string::npos) {
        s.note(rel + " is not a plain SVG picture (no <svg>, or it carries a script): left out");
        continue;
      }
      s.plot(Plot{"scene_" + file_stem(name) + "_" + file_stem(f.stem().string()), name + ": " + f.filename().string(), svg, rel, false});
    } else {
      const auto rows = shear_rows(read_text(f));
      if (rows.empty()) {
        s.note(rel + " has no rows in the direct-shear curve format: not plotted");
        continue;
      }
      GnuplotPlot p;
      p.add_data("curve.dat", rows);
      p.script = "set title " + gp_quote(name + ": direct shear") + "\nset xlabel 'shear displacement (mm)'\n"
                 "set ylabel 'shear stress (kPa)'\nset grid\nset key top left box opaque\n"
                 "plot 'curve.dat' using 1:2 with lines lw 1 lc rgb '#9ecae1' title 'shear stress', "
                 "'curve.dat' using 1:3 with lines lw 2.5 lc rgb '#08519c' title 'smoothed'\n";
      add_plot(s, "shear_curve_" + file_stem(name), name + ": shear stress against displacement (" + rel + ")", p);
    }
  }
  if (!s.blocks.empty()) doc.sections.push_back(std::move(s));
}

}  // namespace seedcal::reports
