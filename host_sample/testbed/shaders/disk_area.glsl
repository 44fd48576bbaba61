// The exact area of a disk intersected with an axis-aligned rectangle: the
// PCF signal's target is the disk's area mean of the nearest-texel shadow
// test (host_sample/testbed/README.md, "The three signals"), so each
// texel's test is weighted by the area of the disk that falls in it.
// Written in the subset GLSL shares with C++ so that a test can compile
// this very file in double (disk_area_test.cpp) and check it against direct
// integration: no array constructors, only sqrt/asin/abs/min/max/clamp.
#ifndef RRC_SAMPLE_DISK_AREA_GLSL
#define RRC_SAMPLE_DISK_AREA_GLSL

// Integral of sqrt(r^2 - x^2) from 0 to x, |x| <= r.
float disk_half_chord_integral(float x, float r) {
    return 0.5 * (x * sqrt(max(r * r - x * x, 0.0)) + r * r * asin(clamp(x / r, -1.0, 1.0)));
}

// Area of {x^2 + y^2 <= r^2} inside [x0, x1] x [y0, y1]: integrate over x the
// length of [y0, y1] inside [-h(x), h(x)], h = sqrt(r^2 - x^2).  Where h(x)
// crosses |y0| or |y1| the integrand changes form; between those break points
// each bound is either constant or +-h, so each piece integrates exactly.
float disk_rect_area(float r, float x0, float x1, float y0, float y1) {
    float a = max(x0, -r), b = min(x1, r);
    if (a >= b || y0 >= y1) return 0.0;
    float cuts[6];
    int n = 0;
    cuts[n++] = a;
    for (int i = 0; i < 2; ++i) {
        float y = i == 0 ? y0 : y1;
        if (abs(y) < r) {
            float c = sqrt(r * r - y * y);
            if (-c > a && -c < b) cuts[n++] = -c;
            if (c > a && c < b) cuts[n++] = c;
        }
    }
    cuts[n++] = b;
    for (int i = 1; i < n; ++i)  // insertion sort: at most 6 values
        for (int j = i; j > 0 && cuts[j - 1] > cuts[j]; --j) {
            float t = cuts[j];
            cuts[j] = cuts[j - 1];
            cuts[j - 1] = t;
        }
    float area = 0.0;
    for (int i = 0; i + 1 < n; ++i) {
        float lo = cuts[i], hi = cuts[i + 1];
        if (hi <= lo) continue;
        float m = 0.5 * (lo + hi), hm = sqrt(max(r * r - m * m, 0.0));
        // Upper bound min(y1, h) minus lower bound max(y0, -h), clamped at 0 (empty when y0 >= h or y1 <= -h).
        if (y0 >= hm || y1 <= -hm) continue;
        float chords = 0.0, constant = 0.0;  // integrand = chords * h(x) + constant
        if (y1 >= hm) chords += 1.0; else constant += y1;
        if (y0 <= -hm) chords += 1.0; else constant -= y0;
        area += chords * (disk_half_chord_integral(hi, r) - disk_half_chord_integral(lo, r)) + constant * (hi - lo);
    }
    return area;
}

#endif
