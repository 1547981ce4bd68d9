#include "reports/markdown_writer.hpp"

#include <algorithm>

namespace seedcal::reports {
namespace {

// A fence longer than the longest run of backticks in the text.
std::string fence_for(const std::string& text) {
  std::size_t longest = 0, run = 0;
  for (char c : text) {
    run = c == '`' ? run + 1 : 0;
    longest = std::max(longest, run);
  }
  return std::string(std::max<std::size_t>(3, longest + 1), '`');
}

// A link target: spaces and parentheses percent-encoded.
std::string link(const std::string& path) {
  std::string out;
  for (char c : path) {
    if (c == ' ') out += "%20";
    else if (c == '(') out += "%28";
    else if (c == ')') out += "%29";
    else out += c;
  }
  return out;
}

struct MarkdownWriter {
  std::string out;
  void cell(const std::string& text) {
    out += ' ';
    out += escape_markdown(text);
    out += " |";
  }
  void operator()(const Paragraph& p) { out += escape_markdown(p.text) + "\n\n"; }
  void operator()(const Note& n) { out += "> **Note:** " + escape_markdown(n.text) + "\n\n"; }
  void operator()(const Preformatted& p) {
    if (!p.caption.empty()) out += "**" + escape_markdown(p.caption) + "**\n\n";
    const std::string f = fence_for(p.text);
    out += f + "\n" + p.text + (p.text.empty() || p.text.back() == '\n' ? "" : "\n") + f + "\n\n";
  }
  void operator()(const Table& t) {
    out += "**";
    out += escape_markdown(t.caption);
    out += "** ([CSV](" + link("report/" + t.id + ".csv") + "))\n\n|";
    for (const auto& c : t.columns) cell(c);
    out += "\n|";
    for (std::size_t i = 0; i < t.columns.size(); ++i) out += " --- |";
    out += "\n";
    for (const auto& r : t.rows) {
      out += "|";
      for (const auto& c : r) cell(c);
      out += "\n";
    }
    out += "\n";
    for (const auto& n : t.notes) {
      out += '*';
      out += escape_markdown(n);
      out += "*\n\n";
    }
  }
  void operator()(const Plot& p) {
    out += "![" + escape_markdown(p.caption) + "](" + link(p.file) + ")\n\n*" + escape_markdown(p.caption) + "*\n\n";
  }
};

}  // namespace

std::string escape_markdown(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '\\': case '`': case '*': case '_': case '[': case ']': case '<': case '>': case '|': case '#':
        out += '\\';
        out += c;
        break;
      case '\n': case '\r': out += ' '; break;
      default: out += c;
    }
  }
  return out;
}

std::string render_markdown(const Document& doc) {
  MarkdownWriter w;
  w.out = "# " + escape_markdown(doc.title) + "\n\n";
  for (const auto& line : doc.subtitle) w.out += escape_markdown(line) + "  \n";
  if (!doc.subtitle.empty()) w.out += "\n";
  for (const auto& s : doc.sections) w.out += "- [" + escape_markdown(s.title) + "](#" + s.id + ")\n";
  w.out += "\n";
  for (const auto& s : doc.sections) {
    w.out += "<a id=\"" + s.id + "\"></a>\n\n## " + escape_markdown(s.title) + "\n\n";
    for (const auto& b : s.blocks) std::visit(w, b);
  }
  return w.out;
}

}  // namespace seedcal::reports
