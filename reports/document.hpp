#pragma once
// What a report says, independent of its format: sections of blocks (paragraphs, notes, key-value
// lists, tables, plots, preformatted text). html_writer and markdown_writer render the same
// Document, so the two files never disagree.
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "reports/table.hpp"

namespace seedcal::reports {

struct Paragraph {
  std::string text;
};

// A remark about what the report could not show (missing data, an older store, a plot that failed).
struct Note {
  std::string text;
};

struct Preformatted {
  std::string caption;
  std::string text;
};

// An SVG picture: a gnuplot plot the report wrote to report/<id>.svg, or a scene picture already
// in the study directory (file relative to it, written = false).
struct Plot {
  std::string id;
  std::string caption;
  std::string svg;   // the complete SVG file text
  std::string file;  // relative to the study directory ("report/effects_pareto.svg")
  bool written = true;
};

using Block = std::variant<Paragraph, Note, Preformatted, Table, Plot>;

struct Section {
  std::string id;     // HTML anchor
  std::string title;  // the heading
  std::vector<Block> blocks;

  void paragraph(std::string text) { blocks.emplace_back(Paragraph{std::move(text)}); }
  void note(std::string text) { blocks.emplace_back(Note{std::move(text)}); }
  void table(Table t) { blocks.emplace_back(std::move(t)); }
  void plot(Plot p) { blocks.emplace_back(std::move(p)); }
  void preformatted(std::string caption, std::string text) {
    blocks.emplace_back(Preformatted{std::move(caption), std::move(text)});
  }
};

struct Document {
  std::string title;
  std::vector<std::string> subtitle;  // lines under the title (study file, version, date)
  std::vector<Section> sections;
};

}  // namespace seedcal::reports
