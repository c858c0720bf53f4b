#include "analysis/report/svg_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace kneesim::report {
namespace {

const char* const kPalette[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd",
                                "#8c564b", "#e377c2", "#17becf"};

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.1f", v);
  return b;
}

std::string tick_label(double v, double step) {
  char b[32];
  const int decimals = std::max(0, static_cast<int>(std::ceil(-std::log10(step) - 1e-9)));
  std::snprintf(b, sizeof b, "%.*f", decimals, std::abs(v) < 1e-12 * step ? 0.0 : v);
  return b;
}

}  // namespace

std::string html_escape(const std::string& s) {
  std::string o;
  o.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      case '\'': o += "&#39;"; break;
      default: o += c;
    }
  }
  return o;
}

std::vector<double> nice_ticks(double lo, double hi, int target) {
  if (!(hi > lo)) {
    const double pad = std::abs(lo) > 0 ? 0.1 * std::abs(lo) : 1.0;
    lo -= pad;
    hi += pad;
  }
  const double raw = (hi - lo) / std::max(1, target);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    if (m * mag >= raw) {
      step = m * mag;
      break;
    }
  }
  std::vector<double> t;
  for (double v = std::floor(lo / step) * step; v <= hi + 1e-9 * step; v += step) {
    t.push_back(v);
  }
  if (t.back() < hi - 1e-9 * step) t.push_back(t.back() + step);
  if (t.size() < 2) t.push_back(t.back() + step);
  return t;
}

std::string svg_line_plot(const PlotSpec& spec) {
  double xlo = std::numeric_limits<double>::infinity(), xhi = -xlo, ylo = xlo, yhi = -xlo;
  for (const PlotSeries& s : spec.series) {
    for (size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      xlo = std::min(xlo, s.x[i]);
      xhi = std::max(xhi, s.x[i]);
      ylo = std::min(ylo, s.y[i]);
      yhi = std::max(yhi, s.y[i]);
    }
  }
  if (!std::isfinite(xlo)) xlo = 0, xhi = 1, ylo = 0, yhi = 1;
  if (spec.y_from_zero) ylo = std::min(0.0, ylo);
  const std::vector<double> xt = nice_ticks(xlo, xhi), yt = nice_ticks(ylo, yhi);
  const double x0 = xt.front(), x1 = xt.back(), y0 = yt.front(), y1 = yt.back();
  const double left = 62, right = 12, top = spec.series.size() > 1 ? 40 : 26, bottom = 42;
  const double W = spec.width, H = spec.height, pw = W - left - right, ph = H - top - bottom;
  auto X = [&](double x) { return left + (x - x0) / (x1 - x0) * pw; };
  auto Y = [&](double y) { return top + (1.0 - (y - y0) / (y1 - y0)) * ph; };

  std::string o = "<svg class=\"plot\" xmlns=\"http://www.w3.org/2000/svg\" width=\"" +
                   num(W) + "\" height=\"" + num(H) + "\" viewBox=\"0 0 " + num(W) + " " +
                   num(H) + "\" role=\"img\" aria-label=\"" + html_escape(spec.title) + "\">\n";
  o += "<text x=\"" + num(left) + "\" y=\"16\" class=\"ptitle\">" + html_escape(spec.title) +
       "</text>\n";
  // grid and ticks
  for (double v : xt) {
    o += "<line class=\"grid\" x1=\"" + num(X(v)) + "\" x2=\"" + num(X(v)) + "\" y1=\"" +
         num(top) + "\" y2=\"" + num(top + ph) + "\"/>";
    o += "<text class=\"tick\" text-anchor=\"middle\" x=\"" + num(X(v)) + "\" y=\"" +
         num(top + ph + 14) + "\">" + tick_label(v, xt[1] - xt[0]) + "</text>\n";
  }
  for (double v : yt) {
    o += "<line class=\"grid\" x1=\"" + num(left) + "\" x2=\"" + num(left + pw) + "\" y1=\"" +
         num(Y(v)) + "\" y2=\"" + num(Y(v)) + "\"/>";
    o += "<text class=\"tick\" text-anchor=\"end\" x=\"" + num(left - 5) + "\" y=\"" +
         num(Y(v) + 4) + "\">" + tick_label(v, yt[1] - yt[0]) + "</text>\n";
  }
  o += "<rect class=\"frame\" x=\"" + num(left) + "\" y=\"" + num(top) + "\" width=\"" +
       num(pw) + "\" height=\"" + num(ph) + "\"/>\n";
  o += "<text class=\"alabel\" text-anchor=\"middle\" x=\"" + num(left + pw / 2) + "\" y=\"" +
       num(H - 6) + "\">" + html_escape(spec.x_label) + "</text>\n";
  o += "<text class=\"alabel\" text-anchor=\"middle\" transform=\"translate(14," +
       num(top + ph / 2) + ") rotate(-90)\">" + html_escape(spec.y_label) + "</text>\n";
  // series
  int k = 0;
  double legend_x = left;
  for (const PlotSeries& s : spec.series) {
    const std::string colour = s.colour.empty() ? kPalette[k % 8] : s.colour;
    ++k;
    std::string pts;
    std::string dots;
    for (size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      pts += num(X(s.x[i])) + "," + num(Y(s.y[i])) + " ";
      if (s.markers) {
        dots += "<circle cx=\"" + num(X(s.x[i])) + "\" cy=\"" + num(Y(s.y[i])) +
                "\" r=\"2.5\" fill=\"" + colour + "\"/>";
      }
    }
    o += "<polyline fill=\"none\" stroke=\"" + colour + "\" stroke-width=\"1.6\"" +
         (s.dashed ? " stroke-dasharray=\"5,3\"" : "") + " points=\"" + pts + "\"><title>" +
         html_escape(s.name) + "</title></polyline>" + dots + "\n";
    if (spec.series.size() > 1) {
      // legend in a row above the frame, so it never hides a curve
      o += "<line x1=\"" + num(legend_x) + "\" x2=\"" + num(legend_x + 16) + "\" y1=\"" +
           num(top - 8) + "\" y2=\"" + num(top - 8) + "\" stroke=\"" + colour +
           "\" stroke-width=\"2\"" + (s.dashed ? " stroke-dasharray=\"5,3\"" : "") + "/>";
      o += "<text class=\"legend\" x=\"" + num(legend_x + 19) + "\" y=\"" + num(top - 4) + "\">" +
           html_escape(s.name) + "</text>\n";
      legend_x += 30 + 6.2 * static_cast<double>(s.name.size());
    }
  }
  o += "</svg>\n";
  return o;
}

}  // namespace kneesim::report
