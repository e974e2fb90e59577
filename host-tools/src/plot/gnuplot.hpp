// SPDX-License-Identifier: MIT
#pragma once
// PNG plots through gnuplot (Debian's gnuplot-nox, pngcairo terminal). The data travel inline in the
// script (gnuplot 5 data blocks), so no temporary files are left behind.
#include <string>
#include <vector>

namespace jacobid::plot {

struct Series {
    std::string title;
    std::vector<double> x;
    std::vector<double> y;
    std::string style = "lines";  // any gnuplot 'with' clause, e.g. "lines lw 2", "points pt 7 ps 0.3"
};

struct Panel {
    std::string title;
    std::string xlabel;
    std::string ylabel;
    bool log_x = false;
    bool log_y = false;
    std::vector<Series> series;
    std::string extra;  // raw gnuplot commands for this panel (ranges, key position ...)
};

// Renders the panels stacked vertically into one PNG. Throws std::runtime_error when gnuplot is missing or
// fails (with its exit status).
void render_png(const std::string& png_path, const std::vector<Panel>& panels, int width = 1100, int panel_height = 380);

// The gnuplot script render_png would run (for tests and for users who want to tweak a plot).
std::string gnuplot_script(const std::string& png_path, const std::vector<Panel>& panels, int width, int panel_height);

}  // namespace jacobid::plot
