#pragma once
/// \file plot.hpp
/// Minimal self-contained SVG plots of the studies' figures (studies/figure.hpp:
/// log-log scatter and lines). No external dependency: the SVG is text, inlined
/// as is into report.html.

#include <qverify/studies/figure.hpp>

#include <string>
#include <vector>

namespace qverify {

/// SVG text of the plot. Zero values on a log axis are drawn on a floor line
/// below the smallest non-zero value, labelled "0".
std::string render_svg(const Plot& plot);

/// Escapes &, <, > and quotes for HTML/SVG text.
std::string html_escape(const std::string& s);

}  // namespace qverify
