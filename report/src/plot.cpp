#include <qverify/report/plot.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace qverify {

std::string html_escape(const std::string& s) {
  std::string o;
  for (char c : s) {
    switch (c) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      default: o += c;
    }
  }
  return o;
}

namespace {
std::string fmt(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}
std::string tick_label(double v, bool log) {
  if (!log) return fmt("%g", v);
  const int e = static_cast<int>(std::lround(v));
  return "1e" + std::to_string(e);
}
}  // namespace

std::string render_svg(const Plot& p) {
  const double L = 80, R = 190, T = 40, B = 56;  // margins (legend on the right)
  const double W = p.width - L - R, H = p.height - T - B;
  auto tx = [&](double x) { return p.log_x ? std::log10(x) : x; };
  auto ty = [&](double y) { return p.log_y ? std::log10(y) : y; };
  double xmin = std::numeric_limits<double>::infinity(), xmax = -xmin, ymin = xmin, ymax = -xmin;
  bool has_zero = false;
  for (const auto& s : p.series)
    for (const auto& [x, y] : s.points) {
      if (!std::isfinite(x) || !std::isfinite(y) || (p.log_x && x <= 0)) continue;
      xmin = std::min(xmin, tx(x));
      xmax = std::max(xmax, tx(x));
      if (p.log_y && y <= 0) {
        has_zero = true;
        continue;
      }
      ymin = std::min(ymin, ty(y));
      ymax = std::max(ymax, ty(y));
    }
  if (!std::isfinite(xmin)) xmin = 0, xmax = 1;
  if (!std::isfinite(ymin)) ymin = -1, ymax = 0;
  if (p.log_x) xmin = std::floor(xmin), xmax = std::ceil(xmax);
  if (p.log_y) ymin = std::floor(ymin), ymax = std::ceil(ymax);
  if (xmax <= xmin) xmax = xmin + 1;
  if (ymax <= ymin) ymax = ymin + 1;
  const double floor_y = has_zero ? ymin - std::max(1.0, (ymax - ymin) * 0.08) : ymin;
  const double y_lo = floor_y;
  auto X = [&](double x) { return L + (tx(x) - xmin) / (xmax - xmin) * W; };
  auto Y = [&](double y) {
    const double v = (p.log_y && y <= 0) ? floor_y : ty(y);
    return T + H - (v - y_lo) / (ymax - y_lo) * H;
  };
  std::string s = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + std::to_string(p.width) + "\" height=\"" +
                  std::to_string(p.height) + "\" viewBox=\"0 0 " + std::to_string(p.width) + " " +
                  std::to_string(p.height) + "\" font-family=\"sans-serif\" font-size=\"11\">\n";
  s += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  s += "<text x=\"" + fmt("%.1f", L + W / 2) + "\" y=\"22\" text-anchor=\"middle\" font-size=\"14\">" + html_escape(p.title) +
       "</text>\n";
  // grid and ticks
  const int xsteps = static_cast<int>(xmax - xmin);
  for (int i = 0; i <= (p.log_x ? xsteps : 4); ++i) {
    const double v = p.log_x ? xmin + i : xmin + (xmax - xmin) * i / 4;
    const double px = L + (v - xmin) / (xmax - xmin) * W;
    s += "<line x1=\"" + fmt("%.1f", px) + "\" y1=\"" + fmt("%.1f", T) + "\" x2=\"" + fmt("%.1f", px) + "\" y2=\"" +
         fmt("%.1f", T + H) + "\" stroke=\"#e6e6e6\"/>\n";
    s += "<text x=\"" + fmt("%.1f", px) + "\" y=\"" + fmt("%.1f", T + H + 16) + "\" text-anchor=\"middle\">" +
         tick_label(v, p.log_x) + "</text>\n";
  }
  const int yspan = static_cast<int>(ymax - ymin);
  const int ystep = std::max(1, yspan / 10);
  for (int i = 0; i <= (p.log_y ? yspan : 4); i += (p.log_y ? ystep : 1)) {
    const double v = p.log_y ? ymin + i : ymin + (ymax - ymin) * i / 4;
    const double py = T + H - (v - y_lo) / (ymax - y_lo) * H;
    s += "<line x1=\"" + fmt("%.1f", L) + "\" y1=\"" + fmt("%.1f", py) + "\" x2=\"" + fmt("%.1f", L + W) + "\" y2=\"" +
         fmt("%.1f", py) + "\" stroke=\"#e6e6e6\"/>\n";
    s += "<text x=\"" + fmt("%.1f", L - 6) + "\" y=\"" + fmt("%.1f", py + 4) + "\" text-anchor=\"end\">" +
         tick_label(v, p.log_y) + "</text>\n";
  }
  if (has_zero) {
    const double py = T + H - (floor_y - y_lo) / (ymax - y_lo) * H;
    s += "<line x1=\"" + fmt("%.1f", L) + "\" y1=\"" + fmt("%.1f", py) + "\" x2=\"" + fmt("%.1f", L + W) + "\" y2=\"" +
         fmt("%.1f", py) + "\" stroke=\"#999\" stroke-dasharray=\"4 3\"/>\n";
    s += "<text x=\"" + fmt("%.1f", L - 6) + "\" y=\"" + fmt("%.1f", py + 4) + "\" text-anchor=\"end\">0 (exact)</text>\n";
  }
  s += "<rect x=\"" + fmt("%.1f", L) + "\" y=\"" + fmt("%.1f", T) + "\" width=\"" + fmt("%.1f", W) + "\" height=\"" +
       fmt("%.1f", H) + "\" fill=\"none\" stroke=\"#333\"/>\n";
  s += "<text x=\"" + fmt("%.1f", L + W / 2) + "\" y=\"" + fmt("%.1f", p.height - 14.0) + "\" text-anchor=\"middle\">" +
       html_escape(p.x_label) + "</text>\n";
  s += "<text transform=\"translate(18," + fmt("%.1f", T + H / 2) + ") rotate(-90)\" text-anchor=\"middle\">" +
       html_escape(p.y_label) + "</text>\n";
  for (const auto& [x, label] : p.x_marks) {
    if (p.log_x && x <= 0) continue;
    const double px = X(x);
    s += "<line x1=\"" + fmt("%.1f", px) + "\" y1=\"" + fmt("%.1f", T) + "\" x2=\"" + fmt("%.1f", px) + "\" y2=\"" +
         fmt("%.1f", T + H) + "\" stroke=\"#c00\" stroke-dasharray=\"6 3\"/>\n";
    s += "<text x=\"" + fmt("%.1f", px + 3) + "\" y=\"" + fmt("%.1f", T + 12) + "\" fill=\"#c00\">" + html_escape(label) +
         "</text>\n";
  }
  // series
  int legend = 0;
  for (const auto& ser : p.series) {
    std::vector<std::pair<double, double>> pts;
    for (const auto& [x, y] : ser.points)
      if (std::isfinite(x) && std::isfinite(y) && !(p.log_x && x <= 0)) pts.emplace_back(x, y);
    if (ser.line && pts.size() > 1) {
      s += "<polyline class=\"series\" fill=\"none\" stroke=\"" + ser.color + "\" stroke-width=\"1.6\"" +
           (ser.dashed ? " stroke-dasharray=\"5 3\"" : "") + " points=\"";
      for (const auto& [x, y] : pts) s += fmt("%.1f", X(x)) + "," + fmt("%.1f", Y(y)) + " ";
      s += "\"/>\n";
    }
    if (ser.markers)
      for (std::size_t i = 0; i < pts.size(); ++i) {
        s += "<circle class=\"point\" cx=\"" + fmt("%.1f", X(pts[i].first)) + "\" cy=\"" + fmt("%.1f", Y(pts[i].second)) +
             "\" r=\"3.5\" fill=\"" + ser.color + "\"><title>" + html_escape(ser.name) + ": x=" + fmt("%.3g", pts[i].first) +
             ", y=" + fmt("%.3g", pts[i].second) + "</title></circle>\n";
        if (i < ser.labels.size() && !ser.labels[i].empty())
          s += "<text x=\"" + fmt("%.1f", X(pts[i].first) + 5) + "\" y=\"" +
               fmt("%.1f", Y(pts[i].second) + (ser.labels_below ? 14 : -5)) +
               "\" font-size=\"10\" fill=\"#333\">" + html_escape(ser.labels[i]) + "</text>\n";
      }
    const double ly = T + 10 + 16 * legend++;
    s += "<line x1=\"" + fmt("%.1f", L + W + 12) + "\" y1=\"" + fmt("%.1f", ly) + "\" x2=\"" + fmt("%.1f", L + W + 32) +
         "\" y2=\"" + fmt("%.1f", ly) + "\" stroke=\"" + ser.color + "\" stroke-width=\"2\"" +
         (ser.dashed ? " stroke-dasharray=\"5 3\"" : "") + "/>\n";
    s += "<text x=\"" + fmt("%.1f", L + W + 38) + "\" y=\"" + fmt("%.1f", ly + 4) + "\">" + html_escape(ser.name) + "</text>\n";
  }
  s += "</svg>\n";
  return s;
}

}  // namespace qverify
