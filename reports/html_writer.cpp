#include "reports/html_writer.hpp"

#include <cstdlib>

namespace seedcal::reports {
namespace {

void replace_all(std::string& s, const std::string& from, const std::string& to) {
  for (std::size_t pos = s.find(from); pos != std::string::npos; pos = s.find(from, pos + to.size()))
    s.replace(pos, from.size(), to);
}

bool looks_numeric(const std::string& s) {
  if (s.empty() || s == "n/a") return s == "n/a";
  char* end = nullptr;
  std::strtod(s.c_str(), &end);
  return end && *end == '\0';
}

const char* kStyle = R"(body{font-family:sans-serif;max-width:1100px;margin:1em auto;padding:0 1em;color:#222;line-height:1.4}
h1{font-size:1.6em;margin-bottom:.2em}h2{border-bottom:1px solid #bbb;padding-bottom:.2em;margin-top:2em}
p.subtitle{color:#555;margin:.1em 0}nav ol{columns:2}
table{border-collapse:collapse;margin:.5em 0 1em;font-size:.9em}
caption{text-align:left;font-weight:bold;padding:.3em 0}
th,td{border:1px solid #ccc;padding:.2em .5em;vertical-align:top}th{background:#f0f0f0}
td.num{text-align:right;font-variant-numeric:tabular-nums;white-space:nowrap}
div.wide{overflow-x:auto}p.note{background:#fff6dd;border-left:4px solid #e0b000;padding:.3em .6em}
p.tablenote{font-size:.85em;color:#444;margin-top:-.6em}
figure{margin:1em 0}figure svg{max-width:100%;height:auto}figcaption{font-size:.9em;color:#333}
pre{background:#f6f6f6;padding:.6em;overflow-x:auto;font-size:.85em}a.csv{font-size:.85em}
)";

struct HtmlWriter {
  std::string out;
  int plot_count = 0;

  void table(const Table& t) {
    out += "<div class=\"wide\"><table id=\"table-" + escape_html(t.id) + "\">\n<caption>" + escape_html(t.caption) +
           " <a class=\"csv\" href=\"report/" + escape_html(t.id) + ".csv\">CSV</a></caption>\n<thead><tr>";
    for (const auto& c : t.columns) out += "<th>" + escape_html(c) + "</th>";
    out += "</tr></thead>\n<tbody>\n";
    for (const auto& r : t.rows) {
      out += "<tr>";
      for (const auto& c : r) out += (looks_numeric(c) ? "<td class=\"num\">" : "<td>") + escape_html(c) + "</td>";
      out += "</tr>\n";
    }
    out += "</tbody></table></div>\n";
    for (const auto& n : t.notes) out += "<p class=\"tablenote\">" + escape_html(n) + "</p>\n";
  }

  void operator()(const Paragraph& p) { out += "<p>" + escape_html(p.text) + "</p>\n"; }
  void operator()(const Note& n) { out += "<p class=\"note\">" + escape_html(n.text) + "</p>\n"; }
  void operator()(const Preformatted& p) {
    if (!p.caption.empty()) out += "<p><b>" + escape_html(p.caption) + "</b></p>\n";
    out += "<pre>" + escape_html(p.text) + "</pre>\n";
  }
  void operator()(const Table& t) { table(t); }
  void operator()(const Plot& p) {
    ++plot_count;
    out += "<figure id=\"plot-" + escape_html(p.id) + "\">\n" +
           inline_svg(p.svg, std::string("p") + std::to_string(plot_count) + "-", p.caption) + "\n<figcaption>" +
           escape_html(p.caption) + " (<a href=\"" + escape_html(p.file) + "\">" + escape_html(p.file) +
           "</a>)</figcaption>\n</figure>\n";
  }
};

}  // namespace

std::string escape_html(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string inline_svg(const std::string& svg, const std::string& id_prefix, const std::string& title) {
  const std::size_t start = svg.find("<svg");
  std::string s = start == std::string::npos ? svg : svg.substr(start);
  for (const char* q : {"'", "\""}) {
    replace_all(s, std::string(" id=") + q, std::string(" id=") + q + id_prefix);
    replace_all(s, std::string("href=") + q + "#", std::string("href=") + q + "#" + id_prefix);
  }
  replace_all(s, "url(#", "url(#" + id_prefix);
  const std::size_t t0 = s.find("<title>"), t1 = s.find("</title>");
  if (t0 != std::string::npos && t1 != std::string::npos && t1 > t0)
    s.replace(t0, t1 + 8 - t0, "<title>" + escape_html(title) + "</title>");
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  return s;
}

std::string render_html(const Document& doc) {
  HtmlWriter w;
  w.out = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" + escape_html(doc.title) +
          "</title>\n<style>\n" + kStyle + "</style>\n</head>\n<body>\n<h1>" + escape_html(doc.title) + "</h1>\n";
  for (const auto& line : doc.subtitle) w.out += "<p class=\"subtitle\">" + escape_html(line) + "</p>\n";
  w.out += "<nav><ol>\n";
  for (const auto& s : doc.sections)
    w.out += "<li><a href=\"#" + escape_html(s.id) + "\">" + escape_html(s.title) + "</a></li>\n";
  w.out += "</ol></nav>\n";
  for (const auto& s : doc.sections) {
    w.out += "<section id=\"" + escape_html(s.id) + "\">\n<h2>" + escape_html(s.title) + "</h2>\n";
    for (const auto& b : s.blocks) std::visit(w, b);
    w.out += "</section>\n";
  }
  w.out += "</body>\n</html>\n";
  return w.out;
}

}  // namespace seedcal::reports
