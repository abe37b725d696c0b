// The report as one self-contained HTML file: APA-style tables, the figures inline as SVG,
// and every number in a span that names its source (data-src), so that it can be checked
// against the analysis.
#include <string>

#include "studies/report/report_document.h"

namespace handlab::studies {
namespace {

std::string escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string line_html(const ReportLine& line) {
  std::string out;
  for (const ReportText& t : line) {
    if (t.source.empty()) {
      out += escape(t.text);
    } else {
      out += "<span class=\"n\" data-src=\"" + escape(t.source) + "\"";
      if (t.relation != '=')
        out += std::string(" data-rel=\"") + (t.relation == '<' ? "&lt;" : "&gt;") + "\"";
      out += ">" + escape(t.text) + "</span>";
    }
  }
  return out;
}

}  // namespace

std::string report_table_html(const ReportTable& t) {
  std::string out = "<table>\n<caption>" + escape(t.caption) + "</caption>\n<thead><tr>";
  for (std::size_t c = 0; c < t.header.size(); ++c)
    out +=
        std::string(t.numeric(c) ? "<th class=\"num\">" : "<th>") + escape(t.header[c]) + "</th>";
  out += "</tr></thead>\n<tbody>\n";
  for (const auto& row : t.rows) {
    out += "<tr>";
    for (std::size_t c = 0; c < row.size(); ++c)
      out +=
          std::string(t.numeric(c) ? "<td class=\"num\">" : "<td>") + line_html(row[c]) + "</td>";
    out += "</tr>\n";
  }
  out += "</tbody>\n</table>\n";
  if (!t.note.empty()) out += "<p class=\"note\"><i>Note.</i> " + escape(t.note) + "</p>\n";
  return out;
}

void write_report_html(const ReportDocument& doc,
                       const std::function<std::string(const ReportFigure&)>& figure_svg,
                       std::ostream& out) {
  out << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>"
      << escape(doc.title) << "</title>\n<style>\n"
      << "body{font-family:'DejaVu Serif',Georgia,serif;max-width:52em;margin:2em auto;"
         "padding:0 1em;color:#111;line-height:1.45}\n"
         "h1{font-size:1.6em;margin-bottom:.2em}h2{font-size:1.25em;margin-top:1.6em;"
         "border-bottom:1px solid #999}h3{font-size:1.05em}\n"
         ".subtitle{color:#444;margin-top:0}\n"
         "table{border-collapse:collapse;margin:1em 0;font-size:.92em}\n"
         "caption{text-align:left;font-style:italic;padding-bottom:.3em}\n"
         "thead th{border-top:2px solid #111;border-bottom:1px solid #111;padding:.25em .6em;"
         "text-align:left}\n"
         "tbody tr:last-child td{border-bottom:2px solid #111}\n"
         "td{padding:.2em "
         ".6em;vertical-align:top}td.num,th.num{text-align:right;white-space:nowrap}\n"
         ".note{font-size:.88em;margin-top:-.6em}\n"
         "figure{margin:1.2em 0}figure svg{max-width:100%;height:auto}\n"
         "figcaption{font-size:.92em}\n"
         "@media print{body{margin:0}h2{break-after:avoid}figure,table{break-inside:avoid}}\n"
      << "</style>\n</head>\n<body>\n<h1>" << escape(doc.title) << "</h1>\n<p class=\"subtitle\">"
      << escape(doc.subtitle) << "</p>\n";
  for (const ReportBlock& b : doc.blocks) {
    switch (b.kind) {
      case ReportBlock::Kind::kHeading:
        out << (b.level == 1 ? "<h2>" : "<h3>") << line_html(b.text)
            << (b.level == 1 ? "</h2>\n" : "</h3>\n");
        break;
      case ReportBlock::Kind::kParagraph:
        out << "<p>" << line_html(b.text) << "</p>\n";
        break;
      case ReportBlock::Kind::kTable:
        out << report_table_html(b.table);
        break;
      case ReportBlock::Kind::kFigure: {
        out << "<figure id=\"" << escape(b.figure.id) << "\">\n";
        if (figure_svg) out << figure_svg(b.figure) << "\n";
        out << "<figcaption>" << escape(b.figure.caption) << "</figcaption>\n</figure>\n";
        break;
      }
    }
  }
  out << "</body>\n</html>\n";
}

}  // namespace handlab::studies
