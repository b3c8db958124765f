// Inline SVG charts written by hand: no scripts, no external fonts, tooltips as <title>.
#include "reports/svg.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "reports/html.h"

namespace cbr::reports {

namespace {

// Chart frame (SVG user units; the SVG scales to its container's width).
struct Frame {
    double w, h, left, right, top, bottom;
    double x0() const { return left; }
    double x1() const { return w - right; }
    double y0() const { return h - bottom; }  // plot bottom
    double y1() const { return top; }         // plot top
};

struct Scale {
    double d0 = 0, d1 = 1, r0 = 0, r1 = 1;
    double operator()(double v) const { return d1 == d0 ? (r0 + r1) / 2 : r0 + (v - d0) / (d1 - d0) * (r1 - r0); }
};

std::string n1(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1f", v);
    return buf;
}

// Appends one path command ("M x y" or "L x y").
void pathTo(std::string& d, bool line, double x, double y) {
    d += line ? 'L' : 'M';
    d += n1(x);
    d += ' ';
    d += n1(y);
}

std::string svgOpen(const Frame& f, const std::string& label) {
    return "<svg class=\"chart\" viewBox=\"0 0 " + n1(f.w) + " " + n1(f.h) + "\" role=\"img\" aria-label=\"" +
           esc(label) + "\">";
}

// [lo, hi] over the finite values, padded; a flat or empty range still gets a span.
std::pair<double, double> finiteRange(const std::vector<double>& values, double pad_fraction) {
    double lo = INFINITY, hi = -INFINITY;
    for (double v : values)
        if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
    if (!std::isfinite(lo)) return {0, 1};
    if (hi - lo < 1e-12) {
        double span = std::max(std::abs(lo) * 0.05, 1e-3);
        return {lo - span, hi + span};
    }
    double pad = (hi - lo) * pad_fraction;
    return {lo - pad, hi + pad};
}

void gridAndAxes(std::string& out, const Frame& f, const Scale& xs, const Scale& ys, const std::vector<double>& xticks,
                 const std::vector<double>& yticks, const std::string& x_label, const std::string& y_label) {
    out += "<g class=\"grid\">";
    for (double t : yticks) {
        double y = ys(t);
        out += "<line x1=\"" + n1(f.x0()) + "\" x2=\"" + n1(f.x1()) + "\" y1=\"" + n1(y) + "\" y2=\"" + n1(y) + "\"/>";
    }
    out += "</g><g class=\"axis\">";
    out += "<line x1=\"" + n1(f.x0()) + "\" x2=\"" + n1(f.x1()) + "\" y1=\"" + n1(f.y0()) + "\" y2=\"" + n1(f.y0()) +
           "\"/>";
    out += "<line x1=\"" + n1(f.x0()) + "\" x2=\"" + n1(f.x0()) + "\" y1=\"" + n1(f.y1()) + "\" y2=\"" + n1(f.y0()) +
           "\"/>";
    for (double t : yticks)
        out += "<text x=\"" + n1(f.x0() - 5) + "\" y=\"" + n1(ys(t) + 3.5) + "\" text-anchor=\"end\">" +
               esc(fmtShort(t)) + "</text>";
    for (double t : xticks)
        out += "<text x=\"" + n1(xs(t)) + "\" y=\"" + n1(f.y0() + 14) + "\" text-anchor=\"middle\">" +
               esc(fmtShort(t)) + "</text>";
    out += "<text class=\"label\" x=\"" + n1((f.x0() + f.x1()) / 2) + "\" y=\"" + n1(f.h - 4) +
           "\" text-anchor=\"middle\">" + esc(x_label) + "</text>";
    out += "<text class=\"label\" transform=\"translate(12 " + n1((f.y0() + f.y1()) / 2) +
           ") rotate(-90)\" text-anchor=\"middle\">" + esc(y_label) + "</text>";
    out += "</g>";
}

std::vector<double> integerTicks(double lo, double hi) {
    std::vector<double> out;
    for (double t : niceTicks(lo, hi, 8))
        if (std::abs(t - std::round(t)) < 1e-9) out.push_back(t);
    if (out.empty()) out.push_back(std::round(lo));
    return out;
}

std::vector<double> ticksInside(double lo, double hi, int target) {
    std::vector<double> out;
    for (double t : niceTicks(lo, hi, target))
        if (t >= lo - 1e-12 && t <= hi + 1e-12) out.push_back(t);
    return out;
}

// The lane above the plot where infinite values sit.
void infinityLane(std::string& out, const Frame& f, double lane_y) {
    out += "<g class=\"inf-lane\"><line x1=\"" + n1(f.x0()) + "\" x2=\"" + n1(f.x1()) + "\" y1=\"" + n1(lane_y) +
           "\" y2=\"" + n1(lane_y) + "\"/><text x=\"" + n1(f.x0() - 5) + "\" y=\"" + n1(lane_y + 3.5) +
           "\" text-anchor=\"end\">\u221e</text></g>";
}

std::string triangle(double x, double y, const std::string& color, const std::string& tip) {
    return "<path d=\"M" + n1(x) + " " + n1(y - 4.5) + "L" + n1(x + 4) + " " + n1(y + 2.5) + "L" + n1(x - 4) + " " +
           n1(y + 2.5) + "Z\" fill=\"" + esc(color) + "\"><title>" + esc(tip) + "</title></path>";
}

}  // namespace

std::vector<double> niceTicks(double lo, double hi, int target) {
    if (!std::isfinite(lo) || !std::isfinite(hi)) return {};
    if (hi < lo) std::swap(lo, hi);
    if (hi - lo < 1e-12) return {lo};
    double raw = (hi - lo) / std::max(1, target);
    double mag = std::pow(10.0, std::floor(std::log10(raw)));
    double step = mag;
    for (double m : {1.0, 2.0, 5.0, 10.0})
        if (m * mag >= raw) {
            step = m * mag;
            break;
        }
    std::vector<double> out;
    for (double t = std::ceil(lo / step) * step; t <= hi + step * 1e-9 && out.size() < 50; t += step)
        out.push_back(std::abs(t) < step * 1e-9 ? 0.0 : t);
    return out;
}

std::string lineChartSvg(const LineChart& c) {
    Frame f{640, 220, 58, 14, 10, 36};
    std::vector<double> all;
    bool any_inf = false;
    for (const auto& s : c.series)
        for (const auto& v : s.y)
            if (v) {
                if (std::isfinite(*v)) all.push_back(*v);
                else if (!std::isnan(*v)) any_inf = true;
            }
    auto [lo, hi] = finiteRange(all, 0.06);
    if (c.y_min) lo = *c.y_min;
    if (c.y_max) hi = *c.y_max;
    double lane_y = f.top + 4;
    if (any_inf) f.top += 16;

    double xmin = c.x.empty() ? 0 : *std::min_element(c.x.begin(), c.x.end());
    double xmax = c.x.empty() ? 1 : *std::max_element(c.x.begin(), c.x.end());
    Scale xs{xmin, xmax, f.x0() + 6, f.x1() - 6};
    auto yticks = ticksInside(lo, hi, 5);
    Scale ys{lo, hi, f.y0(), f.y1()};

    std::string out = svgOpen(f, c.y_label + " per " + c.x_label);
    gridAndAxes(out, f, xs, ys, c.x_integer ? integerTicks(xmin, xmax) : niceTicks(xmin, xmax, 6), yticks, c.x_label,
                c.y_label);
    if (any_inf) infinityLane(out, f, lane_y);

    size_t points_total = 0;
    for (const auto& s : c.series) points_total += s.y.size();
    // Long sequences (hundreds to thousands of frames): a dot per point would hide the line,
    // so only each series' lowest and highest points get a dot, with their value on hover.
    const bool dots = points_total <= 240;
    for (const auto& s : c.series) {
        std::optional<size_t> low, high;
        if (!dots)
            for (size_t i = 0; i < s.y.size() && i < c.x.size(); ++i) {
                const auto& v = s.y[i];
                if (!v || !std::isfinite(*v)) continue;
                if (!low || *v < *s.y[*low]) low = i;
                if (!high || *v > *s.y[*high]) high = i;
            }
        std::string color = esc(s.color);
        out += "<g class=\"series\">";
        std::string path;
        bool pen_down = false;
        size_t run = 0;
        for (size_t i = 0; i < s.y.size() && i < c.x.size(); ++i) {
            std::optional<double> v = s.y[i];
            if (!v || !std::isfinite(*v)) {
                pen_down = false;
                continue;
            }
            double cl = std::clamp(*v, lo, hi);
            pathTo(path, pen_down, xs(c.x[i]), ys(cl));
            pen_down = true;
            ++run;
        }
        if (run > 0)
            out += "<path d=\"" + path + "\" fill=\"none\" stroke=\"" + color + "\" stroke-width=\"1.6\"/>";
        for (size_t i = 0; i < s.y.size() && i < c.x.size(); ++i) {
            std::optional<double> v = s.y[i];
            if (!v || std::isnan(*v)) continue;
            std::string tip = s.name + ", " + c.x_label + " " + fmtShort(c.x[i]) + ": " + fmtShort(*v, 5);
            if (std::isinf(*v)) {
                out += triangle(xs(c.x[i]), *v > 0 ? lane_y : f.y0(), s.color, tip);
            } else if (*v < lo || *v > hi) {
                out += triangle(xs(c.x[i]), ys(std::clamp(*v, lo, hi)), s.color, tip + " (clipped)");
            } else if (dots || i == low || i == high) {
                out += "<circle cx=\"" + n1(xs(c.x[i])) + "\" cy=\"" + n1(ys(*v)) + "\" r=\"2.2\" fill=\"" + color +
                       "\"><title>" + esc(tip) + "</title></circle>";
            }
        }
        out += "</g>";
    }
    return out + "</svg>";
}

std::string stackedChartSvg(const StackedChart& c) {
    Frame f{640, 220, 58, 14, 10, 36};
    const size_t n = c.x.size();
    std::vector<double> totals(n, 0.0);
    for (const auto& l : c.layers)
        for (size_t i = 0; i < n && i < l.y.size(); ++i)
            if (l.y[i] && std::isfinite(*l.y[i])) totals[i] += std::max(0.0, *l.y[i]);
    double hi = 0;
    for (double t : totals) hi = std::max(hi, t);
    if (c.overlay)
        for (const auto& v : c.overlay->y)
            if (v && std::isfinite(*v)) hi = std::max(hi, *v);
    hi = c.y_max ? *c.y_max : (hi > 0 ? hi * 1.05 : 1.0);
    Scale ys{0, hi, f.y0(), f.y1()};
    auto yticks = ticksInside(0, hi, 5);

    const bool areas = c.areas && n >= 2;
    double xmin = n ? c.x.front() : 0, xmax = n ? c.x.back() : 1;
    const double band = (f.x1() - f.x0()) / double(std::max<size_t>(n, 1));
    Scale xs = areas ? Scale{xmin, xmax, f.x0(), f.x1()}
                     : Scale{xmin - 0.5, xmax + 0.5, f.x0(), f.x1()};  // bars: one band per frame

    std::string out = svgOpen(f, c.y_label + " per " + c.x_label);
    gridAndAxes(out, f, xs, ys, integerTicks(xmin, xmax), yticks, c.x_label, c.y_label);

    std::vector<double> base(n, 0.0);
    for (const auto& l : c.layers) {
        std::vector<double> top = base;
        for (size_t i = 0; i < n && i < l.y.size(); ++i)
            if (l.y[i] && std::isfinite(*l.y[i])) top[i] += std::max(0.0, *l.y[i]);
        std::string color = esc(l.color);
        if (areas) {
            std::string d;
            for (size_t i = 0; i < n; ++i) pathTo(d, i > 0, xs(c.x[i]), ys(top[i]));
            for (size_t i = n; i-- > 0;) pathTo(d, true, xs(c.x[i]), ys(base[i]));
            out += "<path d=\"" + d + "Z\" fill=\"" + color + "\" fill-opacity=\"0.85\"><title>" + esc(l.name) +
                   "</title></path>";
        } else {
            out += "<g fill=\"" + color + "\">";
            for (size_t i = 0; i < n; ++i) {
                double h = ys(base[i]) - ys(top[i]);
                if (h <= 0) continue;
                double v = (top[i] - base[i]) * c.value_scale;
                out += "<rect x=\"" + n1(xs(c.x[i]) - band * 0.4) + "\" y=\"" + n1(ys(top[i])) + "\" width=\"" +
                       n1(band * 0.8) + "\" height=\"" + n1(h) + "\"><title>" +
                       esc(c.x_label + " " + fmtShort(c.x[i]) + ", " + l.name + ": " + fmtShort(v) + c.value_unit) +
                       "</title></rect>";
            }
            out += "</g>";
        }
        base = top;
    }
    if (c.overlay) {
        std::string d;
        bool pen = false;
        for (size_t i = 0; i < n && i < c.overlay->y.size(); ++i) {
            const auto& v = c.overlay->y[i];
            if (!v || !std::isfinite(*v)) {
                pen = false;
                continue;
            }
            pathTo(d, pen, xs(c.x[i]), ys(std::min(*v, hi)));
            pen = true;
        }
        if (!d.empty())
            out += "<path d=\"" + d + "\" fill=\"none\" stroke=\"" + esc(c.overlay->color) +
                   "\" stroke-width=\"1.4\" stroke-dasharray=\"4 2\"><title>" + esc(c.overlay->name) + "</title></path>";
    }
    return out + "</svg>";
}

std::vector<size_t> paretoFront(const std::vector<ScatterPoint>& p, bool higher) {
    auto better_or_equal = [higher](double a, double b) { return higher ? a >= b : a <= b; };
    auto strictly_better = [higher](double a, double b) { return higher ? a > b : a < b; };
    auto cost = [&p](size_t i) { return p[i].front_x.value_or(p[i].x); };
    auto usable = [&](size_t i) { return p[i].y && !std::isnan(*p[i].y) && std::isfinite(p[i].x) && std::isfinite(cost(i)); };
    std::vector<size_t> front;
    for (size_t i = 0; i < p.size(); ++i) {
        if (!usable(i)) continue;
        bool dominated = false;
        for (size_t j = 0; j < p.size() && !dominated; ++j) {
            if (j == i || !usable(j)) continue;
            bool no_worse = cost(j) <= cost(i) && better_or_equal(*p[j].y, *p[i].y);
            bool better = cost(j) < cost(i) || strictly_better(*p[j].y, *p[i].y);
            dominated = no_worse && better;
        }
        if (!dominated) front.push_back(i);
    }
    std::sort(front.begin(), front.end(), [&p](size_t a, size_t b) { return p[a].x < p[b].x; });
    return front;
}

namespace {

// The points' labels, where they collide with no point and no earlier label (greedy, first
// fit); `placed` holds the drawn points' centres in point order.
void placePointLabels(std::string& out, const ScatterChart& c, const Frame& f, const std::vector<size_t>& front,
                      const std::vector<std::pair<double, double>>& placed) {
    struct Box {
        double x0, y0, x1, y1;
        bool hits(const Box& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
    };
    std::vector<Box> taken;
    for (const auto& [px, py_] : placed) taken.push_back({px - 7, py_ - 7, px + 7, py_ + 7});
    size_t k = 0;
    for (size_t i = 0; i < c.points.size(); ++i) {
        const auto& p = c.points[i];
        if (!std::isfinite(p.x) || !p.y || std::isnan(*p.y)) continue;
        const auto [x, y] = placed[k++];
        if (c.label_front_only && std::find(front.begin(), front.end(), i) == front.end()) continue;
        const double w = 6.4 * double(p.label.size()), h = 11;
        const struct {
            double dx, dy;
            bool left;
        } tries[] = {{9, -6, false}, {9, 14, false}, {-9, -6, true}, {-9, 14, true},
                     {9, -18, false}, {-9, -18, true}, {9, 26, false}, {-9, 26, true}};
        double lx = x + 9, ly = y - 6;
        bool left = false;
        for (const auto& t : tries) {
            double bx = t.left ? x + t.dx - w : x + t.dx;
            Box b{bx, y + t.dy - 9, bx + w, y + t.dy + h - 9};
            bool inside = b.x0 >= 0 && b.x1 <= f.w && b.y0 >= 16 && b.y1 <= f.y0();
            if (!inside || std::any_of(taken.begin(), taken.end(), [&](const Box& o) { return o.hits(b); })) continue;
            lx = x + t.dx, ly = y + t.dy, left = t.left;
            taken.push_back(b);
            break;
        }
        out += "<text class=\"point-label\" x=\"" + n1(lx) + "\" y=\"" + n1(ly) + "\" text-anchor=\"" +
               (left ? "end" : "start") + "\">" + esc(p.label) + "</text>";
    }
}

}  // namespace

std::string scatterChartSvg(const ScatterChart& c) {
    Frame f{c.width, 250, 52, 16, 26, 36};
    std::vector<double> xs_v, ys_v;
    bool any_inf = false;
    auto onLane = [&](double y) { return std::isinf(y) || (c.lane_above && y > *c.lane_above); };
    for (const auto& p : c.points) {
        if (!std::isfinite(p.x) || !p.y || std::isnan(*p.y)) continue;
        xs_v.push_back(p.x);
        if (!onLane(*p.y)) ys_v.push_back(*p.y);
        else any_inf = true;
    }
    double xhi = 1;
    for (double x : xs_v) xhi = std::max(xhi, x);
    xhi *= 1.12;
    auto [ylo, yhi] = finiteRange(ys_v, 0.12);
    if (!c.y_higher_is_better) ylo = 0.0;  // errors: the reference sits at 0
    double lane_y = f.top + 4;
    if (any_inf) f.top += 16;
    Scale xs{0, xhi, f.x0(), f.x1()};
    Scale ys{ylo, yhi, f.y0(), f.y1()};

    std::string out = svgOpen(f, c.title);
    out += "<text class=\"title\" x=\"" + n1(f.w / 2) + "\" y=\"14\" text-anchor=\"middle\">" + esc(c.title) + "</text>";
    gridAndAxes(out, f, xs, ys, ticksInside(0, xhi, 4), ticksInside(ylo, yhi, 5), c.x_label, c.y_label);
    if (any_inf) infinityLane(out, f, lane_y);

    auto py = [&](double y) {
        if (onLane(y)) return (y > 0) == c.y_higher_is_better ? lane_y : f.y0();
        return ys(y);
    };
    auto front = paretoFront(c.points, c.y_higher_is_better);
    if (front.size() >= 2) {
        std::string d;
        for (size_t k = 0; k < front.size(); ++k)
            pathTo(d, k > 0, xs(c.points[front[k]].x), py(*c.points[front[k]].y));
        out += "<path class=\"pareto\" d=\"" + d + "\"><title>Pareto front</title></path>";
    }
    std::vector<std::pair<double, double>> placed;  // drawn point centres, in point order
    for (size_t i = 0; i < c.points.size(); ++i) {
        const auto& p = c.points[i];
        if (!std::isfinite(p.x) || !p.y || std::isnan(*p.y)) continue;
        bool on_front = std::find(front.begin(), front.end(), i) != front.end();
        double x = xs(p.x), y = py(*p.y);
        std::string tip = p.label + ": " + fmtShort(p.x) + " ms" + (p.note.empty() ? "" : ", " + p.note) + ", " +
                          c.y_label + " " + fmtShort(*p.y, 5) +
                          (on_front ? " (Pareto front)" : " (dominated)");
        if (on_front)
            out += "<circle cx=\"" + n1(x) + "\" cy=\"" + n1(y) + "\" r=\"7\" fill=\"none\" stroke=\"" +
                   esc(p.color) + "\" stroke-width=\"1.2\"/>";
        out += "<circle cx=\"" + n1(x) + "\" cy=\"" + n1(y) + "\" r=\"4\" fill=\"" + esc(p.color) + "\"><title>" +
               esc(tip) + "</title></circle>";
        placed.push_back({x, y});
    }
    placePointLabels(out, c, f, front, placed);
    return out + "</svg>";
}

}  // namespace cbr::reports
