// Rectilinear polygons and rect differences as lists of rects (DBU).
#pragma once

#include <vector>

#include "geom/geom.hpp"

namespace xroute {

// Appends rects covering a rectilinear polygon (horizontal slabs, even-odd
// rule); its bounding box when an edge is slanted; nothing for < 3 points.
void polygonRects(const std::vector<Point>& pts, std::vector<Rect>& out);

// Appends the parts of `r` outside `cut` (up to four rects).
void subtractRect(const Rect& r, const Rect& cut, std::vector<Rect>& out);

}  // namespace xroute
