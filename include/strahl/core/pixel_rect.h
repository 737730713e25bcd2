#pragma once
// Half-open pixel rectangle [x0, x1) x [y0, y1); y = 0 is the top row. Used for
// crop windows and render tiles.

namespace strahl {

struct PixelRect {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    int width() const { return x1 - x0; }
    int height() const { return y1 - y0; }
    bool empty() const { return x1 <= x0 || y1 <= y0; }
    // Whether `r` (not empty) lies wholly inside this rectangle.
    bool contains(const PixelRect& r) const {
        return !r.empty() && r.x0 >= x0 && r.y0 >= y0 && r.x1 <= x1 && r.y1 <= y1;
    }
    long long area() const { return empty() ? 0 : static_cast<long long>(width()) * height(); }
};

}  // namespace strahl
