#include "fetch.h"

#include <algorithm>
#include <cmath>

#include "finish.h"

namespace rrc_ref {

namespace {

// Beyond [-4, size + 3] every tap of every filter clamps to the edge texel, so
// clamping the coordinate there changes no fetch and keeps floor() in int range.
double safe_coord(double p, int size) { return std::min(std::max(p, -4.0), size + 3.0); }

struct Cell {
    int x0, y0;     // top-left bilinear tap (before clamping)
    double fx, fy;  // fractions
};

Cell cell_at(double qx, double qy, int width, int height) {
    double px = safe_coord(qx - 0.5, width), py = safe_coord(qy - 0.5, height);
    double x0 = std::floor(px), y0 = std::floor(py);
    return {static_cast<int>(x0), static_cast<int>(y0), px - x0, py - y0};
}

// Catmull-Rom weights for fraction t (taps i0-1 .. i0+2).
void catmull_rom_weights(double t, double w[4]) {
    double t2 = t * t, t3 = t2 * t;
    w[0] = 0.5 * (-t3 + 2.0 * t2 - t);
    w[1] = 0.5 * (3.0 * t3 - 5.0 * t2 + 2.0);
    w[2] = 0.5 * (-3.0 * t3 + 4.0 * t2 + t);
    w[3] = 0.5 * (t3 - t2);
}

}  // namespace

int nearest_index(double q, int size) {
    if (q < 0.0) return 0;
    if (q >= size) return size - 1;
    return static_cast<int>(std::floor(q));
}

BilinearTaps bilinear_taps(double qx, double qy, int width, int height) {
    const Cell k = cell_at(qx, qy, width, height);
    BilinearTaps t;
    t.x0 = k.x0, t.y0 = k.y0;
    const double w[4] = {(1 - k.fx) * (1 - k.fy), k.fx * (1 - k.fy), (1 - k.fx) * k.fy, k.fx * k.fy};
    for (int n = 0; n < 4; ++n) {
        t.x[n] = std::min(std::max(k.x0 + (n & 1), 0), width - 1);
        t.y[n] = std::min(std::max(k.y0 + (n >> 1), 0), height - 1);
        t.w[n] = w[n];
    }
    return t;
}

double Image::at(int x, int y, unsigned c) const {
    x = std::min(std::max(x, 0), width - 1);
    y = std::min(std::max(y, 0), height - 1);
    return data[(static_cast<size_t>(y) * width + x) * components + c];
}

void resample(const Image& img, rrc_history_filter filter, double qx, double qy, double* out, double blur_g) {
    if (filter == RRC_HISTORY_FILTER_NEAREST) {
        int x = nearest_index(qx, img.width), y = nearest_index(qy, img.height);
        for (unsigned c = 0; c < img.components; ++c) out[c] = img.at(x, y, c);
        return;
    }
    Cell k = cell_at(qx, qy, img.width, img.height);
    if (filter == RRC_HISTORY_FILTER_GAUSSIAN) {
        // Bilinear after the separable blur [g, 1 - 2g, g]: the 4x4 taps of
        // Catmull-Rom with non-negative weights summing to 1 (no clamp).
        double wx[4], wy[4];
        gaussian_weights(k.fx, blur_g, wx);
        gaussian_weights(k.fy, blur_g, wy);
        for (unsigned c = 0; c < img.components; ++c) {
            double sum = 0.0;
            for (int b = 0; b < 4; ++b)
                for (int a = 0; a < 4; ++a) sum += wx[a] * wy[b] * img.at(k.x0 - 1 + a, k.y0 - 1 + b, c);
            out[c] = sum;
        }
        return;
    }
    for (unsigned c = 0; c < img.components; ++c) {
        double t00 = img.at(k.x0, k.y0, c), t10 = img.at(k.x0 + 1, k.y0, c);
        double t01 = img.at(k.x0, k.y0 + 1, c), t11 = img.at(k.x0 + 1, k.y0 + 1, c);
        if (filter != RRC_HISTORY_FILTER_CATMULL_ROM) {
            out[c] = (1 - k.fx) * (1 - k.fy) * t00 + k.fx * (1 - k.fy) * t10 + (1 - k.fx) * k.fy * t01 + k.fx * k.fy * t11;
            continue;
        }
        double wx[4], wy[4], sum = 0.0;
        catmull_rom_weights(k.fx, wx);
        catmull_rom_weights(k.fy, wy);
        for (int b = 0; b < 4; ++b)
            for (int a = 0; a < 4; ++a) sum += wx[a] * wy[b] * img.at(k.x0 - 1 + a, k.y0 - 1 + b, c);
        double lo = std::min(std::min(t00, t10), std::min(t01, t11));
        double hi = std::max(std::max(t00, t10), std::max(t01, t11));
        out[c] = std::min(std::max(sum, lo), hi);  // cannot ring beyond the bilinear taps
    }
}

DepthFetch fetch_depth(const Params& p, const std::vector<float>& depth, Bounded qx, Bounded qy, double scale) {
    const int W = p.width, H = p.height;
    const bool linear = p.mode == RRC_DEPTH_MODE_LINEAR;
    Image img{depth.data(), W, H, 1};
    Bounded px = qx - exact(0.5), py = qy - exact(0.5);
    Cell k = cell_at(qx.v, qy.v, W, H);

    // The interpolated quantity: z, or 1/d for LINEAR (exact on planes).
    auto tap = [&](int x, int y) {
        double d = img.at(x, y, 0);
        return linear ? 1.0 / d : d;
    };
    double t[4] = {tap(k.x0, k.y0), tap(k.x0 + 1, k.y0), tap(k.x0, k.y0 + 1), tap(k.x0 + 1, k.y0 + 1)};
    double w[4] = {(1 - k.fx) * (1 - k.fy), k.fx * (1 - k.fy), (1 - k.fx) * k.fy, k.fx * k.fy};
    double sum = 0.0, magnitude = 0.0;
    for (int n = 0; n < 4; ++n) {
        sum += w[n] * t[n];
        magnitude += w[n] * std::fabs(t[n]);
    }

    // Cells the kernel may use given its position error (1 or 2 per axis).
    double dx = px.err * scale, dy = py.err * scale;
    int xlo = static_cast<int>(std::floor(safe_coord(px.v - dx, W)));
    int xhi = static_cast<int>(std::floor(safe_coord(px.v + dx, W)));
    int ylo = static_cast<int>(std::floor(safe_coord(py.v - dy, H)));
    int yhi = static_cast<int>(std::floor(safe_coord(py.v + dy, H)));
    // A position error of a texel or more leaves the fetch undetermined.
    bool finite_pos = std::isfinite(dx) && std::isfinite(dy) && xhi - xlo <= 1 && yhi - ylo <= 1;

    // Background taps, per candidate cell.
    auto cell_has_background = [&](int x0, int y0) {
        for (int b = 0; b < 2; ++b)
            for (int a = 0; a < 2; ++a)
                if (is_background(p, img.at(x0 + a, y0 + b, 0))) return true;
        return false;
    };
    bool nominal_bg = cell_has_background(k.x0, k.y0);
    bool agree = finite_pos;
    for (int y0 : {ylo, yhi})
        for (int x0 : {xlo, xhi}) agree = agree && cell_has_background(x0, y0) == nominal_bg;

    // Error: rounding of the weighted sum (1 - f and the weight product: 3u on
    // each weight, its product with the tap and three additions: 4u; the 1/d of
    // a LINEAR tap: 1u more), plus the position error times the largest tap step
    // in the cells the kernel may use.
    double steep_x = 0.0, steep_y = 0.0;
    if (finite_pos) {
        for (int y = ylo; y <= yhi + 1; ++y)
            for (int x = xlo; x <= xhi; ++x) steep_x = std::max(steep_x, std::fabs(tap(x + 1, y) - tap(x, y)));
        for (int y = ylo; y <= yhi; ++y)
            for (int x = xlo; x <= xhi + 1; ++x) steep_y = std::max(steep_y, std::fabs(tap(x, y + 1) - tap(x, y)));
    }
    double err = (linear ? 8.0 : 7.0) * kU * magnitude + (finite_pos ? px.err * steep_x + py.err * steep_y : INFINITY);
    Bounded interpolated = rounded(sum, err - kU * std::fabs(sum));  // rounded() re-adds it
    DepthFetch f;
    f.value = linear ? exact(1.0) / interpolated : interpolated;
    f.no_background = {!nominal_bg, agree};
    return f;
}

Decision taps_hold_id(const std::vector<uint32_t>& ids, int W, int H, Bounded qx, Bounded qy, uint32_t id, double scale) {
    auto holds = [&](double x, double y) {
        Cell k = cell_at(x, y, W, H);
        const double w[4] = {(1 - k.fx) * (1 - k.fy), k.fx * (1 - k.fy), (1 - k.fx) * k.fy, k.fx * k.fy};
        for (int n = 0; n < 4; ++n) {
            int tx = std::min(std::max(k.x0 + (n & 1), 0), W - 1), ty = std::min(std::max(k.y0 + (n >> 1), 0), H - 1);
            if (w[n] > 0.0 && ids[static_cast<size_t>(ty) * W + tx] != id) return false;
        }
        return true;
    };
    const bool nominal = holds(qx.v, qy.v);
    const double dx = qx.err * scale, dy = qy.err * scale;
    bool sure = std::isfinite(dx) && std::isfinite(dy);
    for (double sx : {-dx, dx})
        for (double sy : {-dy, dy}) sure = sure && holds(qx.v + sx, qy.v + sy) == nominal;
    return {nominal, sure};
}

}  // namespace rrc_ref
