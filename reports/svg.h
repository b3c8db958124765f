// Inline SVG charts for the HTML report: line charts, stacked bars/areas, error-vs-time scatter.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace cbr::reports {

// One named sequence of values over the chart's x values; nullopt = no value (gap).
struct Series {
    std::string name;
    std::string color;  // CSS colour
    std::vector<std::optional<double>> y;
};

// Per-frame lines. Infinite values (PSNR of identical images) never enter the scale:
// they sit on a marked lane above the plot, drawn as triangles.
struct LineChart {
    std::string y_label;  // with unit, e.g. "PSNR (dB)"
    std::string x_label = "frame";
    std::vector<double> x;
    std::vector<Series> series;
    std::optional<double> y_min, y_max;  // forced bounds, else from the data
    bool x_integer = true;               // integer x ticks (frames); false: 1-2-5 ticks
};
std::string lineChartSvg(const LineChart& chart);

// Layers stacked bottom-up per x (missing values count as 0).
struct StackedChart {
    std::string y_label;
    std::string x_label = "frame";
    std::vector<double> x;
    std::vector<Series> layers;
    std::optional<double> y_max;  // shared scale across charts, else from the data
    bool areas = false;           // false: bars
    std::optional<Series> overlay;  // e.g. the frame total, drawn as a line on top
    std::string value_unit;         // tooltip suffix, e.g. " ms" or "%"
    double value_scale = 1.0;       // tooltip value multiplier (100 for shares in %)
};
std::string stackedChartSvg(const StackedChart& chart);

// Error against run time: one point per variant, the Pareto front drawn through the
// points no other point beats on both axes (x always lower-is-better).
struct ScatterPoint {
    std::string label;
    std::string color;
    double x = 0;
    std::optional<double> y;  // nullopt: not drawn; +-inf: on the infinity lane
    // What the Pareto front is taken on, lower is better (the report: the paired speed-up,
    // negated, while x stays the median time); x when unset.
    std::optional<double> front_x;
    std::string note;  // added to the point's tooltip (e.g. its paired speed-up)
};
struct ScatterChart {
    std::string title;
    std::string x_label;
    std::string y_label;
    bool y_higher_is_better = false;
    std::vector<ScatterPoint> points;
    double width = 320;                  // view-box width (many points: wider)
    bool label_front_only = false;       // label only the Pareto front (many points)
    std::optional<double> lane_above;    // y above this sits on the top lane (e.g. PSNR of near-identical images)
};
std::string scatterChartSvg(const ScatterChart& chart);

// Indices of the Pareto-optimal points (front_x, else x, minimised; y maximised or
// minimised), in order of x; points without a y ignored. Infinite y counts as the best (or
// worst) possible value.
std::vector<size_t> paretoFront(const std::vector<ScatterPoint>& points, bool y_higher_is_better);

// Ticks at 1, 2 or 5 x 10^k covering [lo, hi], about `target` of them.
std::vector<double> niceTicks(double lo, double hi, int target = 5);

}  // namespace cbr::reports
