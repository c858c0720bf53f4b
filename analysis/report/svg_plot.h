// Line plots as inline SVG text for the HTML report: no plotting library in the page, the
// picture is finished when the file is written. Axes carry their labels with units.
#pragma once

#include <string>
#include <vector>

namespace kneesim::report {

struct PlotSeries {
  std::string name;        // legend entry
  std::vector<double> x, y;
  std::string colour;      // CSS colour; "" picks the next of a fixed palette
  bool dashed = false;
  bool markers = false;    // a dot at every point (few points, e.g. one per update)
};

struct PlotSpec {
  std::string title;
  std::string x_label, y_label;  // with units, e.g. "gait cycle (%)", "AP, tibia anterior (mm)"
  std::vector<PlotSeries> series;
  int width = 560, height = 260;  // [px]
  bool y_from_zero = false;       // the y axis starts at 0 (forces, areas, volumes)
};

// "nice" axis ticks (1, 2, 5 x 10^k) covering [lo, hi]; at least two
std::vector<double> nice_ticks(double lo, double hi, int target = 5);

// the plot as an <svg> element (non-finite points are skipped)
std::string svg_line_plot(const PlotSpec& spec);

// escapes &, <, >, " and ' for HTML text and attributes
std::string html_escape(const std::string& s);

}  // namespace kneesim::report
