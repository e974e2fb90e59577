// SPDX-License-Identifier: MIT
#include "plot/gnuplot.hpp"

#include <fmt/core.h>

#include <cstdio>
#include <stdexcept>
#include <sys/wait.h>

namespace jacobid::plot {
namespace {

std::string quoted(const std::string& s) {
    std::string out = "\"";
    for (char c : s) {
        if (c == '"' || c == '\\') out += '\\';
        out += c;
    }
    return out + "\"";
}

}  // namespace

std::string gnuplot_script(const std::string& png_path, const std::vector<Panel>& panels, int width, int panel_height) {
    std::string s;
    // Data blocks first: one per series.
    for (std::size_t p = 0; p < panels.size(); ++p) {
        for (std::size_t i = 0; i < panels[p].series.size(); ++i) {
            const Series& series = panels[p].series[i];
            if (series.x.size() != series.y.size()) throw std::invalid_argument("plot series '" + series.title + "': x and y differ in length");
            s += fmt::format("$d{}_{} << EOD\n", p, i);
            for (std::size_t k = 0; k < series.x.size(); ++k) s += fmt::format("{:.10g} {:.10g}\n", series.x[k], series.y[k]);
            s += "EOD\n";
        }
    }
    s += fmt::format("set terminal pngcairo size {},{} font 'DejaVu Sans,10'\n", width, panel_height * static_cast<int>(panels.size()));
    s += fmt::format("set output {}\n", quoted(png_path));
    if (panels.size() > 1) s += fmt::format("set multiplot layout {},1\n", panels.size());
    for (std::size_t p = 0; p < panels.size(); ++p) {
        const Panel& panel = panels[p];
        s += "reset\nset grid\nset key inside top right opaque box\n";
        s += fmt::format("set title {}\nset xlabel {}\nset ylabel {}\n", quoted(panel.title), quoted(panel.xlabel), quoted(panel.ylabel));
        s += panel.log_x ? "set logscale x\n" : "unset logscale x\n";
        s += panel.log_y ? "set logscale y\n" : "unset logscale y\n";
        s += panel.extra;
        if (!panel.extra.empty() && panel.extra.back() != '\n') s += '\n';
        s += "plot ";
        for (std::size_t i = 0; i < panel.series.size(); ++i) {
            s += fmt::format("{}$d{}_{} using 1:2 with {} title {}", i ? ", " : "", p, i, panel.series[i].style, quoted(panel.series[i].title));
        }
        s += "\n";
    }
    if (panels.size() > 1) s += "unset multiplot\n";
    s += "set output\n";
    return s;
}

void render_png(const std::string& png_path, const std::vector<Panel>& panels, int width, int panel_height) {
    const std::string script = gnuplot_script(png_path, panels, width, panel_height);
    FILE* pipe = popen("gnuplot 2>&1", "w");
    if (!pipe) throw std::runtime_error("cannot start gnuplot");
    const std::size_t written = std::fwrite(script.data(), 1, script.size(), pipe);
    const int status = pclose(pipe);
    if (written != script.size() || status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        const int code = (status != -1 && WIFEXITED(status)) ? WEXITSTATUS(status) : -1;
        throw std::runtime_error(code == 127 ? "gnuplot not found: install it (Debian: apt-get install gnuplot-nox)"
                                             : fmt::format("gnuplot failed (exit status {}) writing {}", code, png_path));
    }
}

}  // namespace jacobid::plot
