#pragma once
// report.html: one self-contained file (inline CSS, inline SVG, no scripts, nothing fetched), with
// a contents list and one <section> per Document section.
#include <string>
#include <string_view>

#include "reports/document.hpp"

namespace seedcal::reports {

// & < > " ' as character references (text and attribute values alike).
std::string escape_html(std::string_view text);

// An SVG file's text for inlining: the XML prolog and doctype dropped, every id (and every
// reference to one: href="#..", url(#..)) prefixed with `id_prefix` so that several plots in one
// page never share an id, and the <title> replaced by `title`.
std::string inline_svg(const std::string& svg, const std::string& id_prefix, const std::string& title);

std::string render_html(const Document& doc);

}  // namespace seedcal::reports
