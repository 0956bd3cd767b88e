// Integer geometry in DEF database units (DBU). Everything in xroute is a DBU
// coordinate unless a name says otherwise (track index, GCell index).
#pragma once

#include <algorithm>
#include <cstdint>
#include <string_view>
#include <vector>

namespace xroute {

using Dbu = int32_t;    // a coordinate or length in DBU
using Area = int64_t;   // an area in DBU^2

// The largest magnitude of a coordinate or length the engine takes from a file, and of any shape it
// places from them (DBU). 2^28 - 1 leaves a factor of eight below int32: a coordinate expanded by
// up to seven lengths (half widths, spacings, extensions, search ranges), or the distance between
// two coordinates each expanded by up to three, still fits a Dbu, and any product of two such
// values fits int64. It is 134 mm at 2,000 DBU per micron (the ISPD contests' unit), 13.4 mm at
// 20,000 (the largest LEF unit). The readers refuse anything beyond it, naming file and line.
inline constexpr Dbu kMaxDbu = (Dbu(1) << 28) - 1;

// Whether |v| <= kMaxDbu.
inline constexpr bool withinDbuRange(int64_t v) { return v >= -int64_t(kMaxDbu) && v <= int64_t(kMaxDbu); }

struct Point {
  Dbu x = 0;  // DBU
  Dbu y = 0;  // DBU
  friend bool operator==(const Point&, const Point&) = default;
};

// Axis-aligned rectangle, closed on all sides: [xlo, xhi] x [ylo, yhi].
struct Rect {
  Dbu xlo = 0, ylo = 0, xhi = 0, yhi = 0;  // DBU

  static Rect fromCorners(Point a, Point b) {
    return {std::min(a.x, b.x), std::min(a.y, b.y), std::max(a.x, b.x), std::max(a.y, b.y)};
  }
  // 64-bit: the span of two coordinates near the ends of int32 overflows a Dbu.
  int64_t width() const { return int64_t(xhi) - xlo; }
  int64_t height() const { return int64_t(yhi) - ylo; }
  // The shorter side (DBU), capped at the largest Dbu.
  Dbu minSide() const { return Dbu(std::min<int64_t>(std::min(width(), height()), INT32_MAX)); }
  Area area() const { return Area(width()) * Area(height()); }
  bool contains(Point p) const { return p.x >= xlo && p.x <= xhi && p.y >= ylo && p.y <= yhi; }
  bool overlaps(const Rect& o) const {
    return xlo <= o.xhi && o.xlo <= xhi && ylo <= o.yhi && o.ylo <= yhi;
  }
  // Conductors in contact: overlap, or a shared boundary segment of positive length (a single
  // common corner point is no contact).
  bool contacts(const Rect& o) const {
    const int64_t ox = int64_t(std::min(xhi, o.xhi)) - std::max(xlo, o.xlo);
    const int64_t oy = int64_t(std::min(yhi, o.yhi)) - std::max(ylo, o.ylo);
    return ox >= 0 && oy >= 0 && (ox > 0 || oy > 0);
  }
  Rect translated(Point d) const { return {xlo + d.x, ylo + d.y, xhi + d.x, yhi + d.y}; }
  void expandToInclude(const Rect& o) {
    xlo = std::min(xlo, o.xlo);
    ylo = std::min(ylo, o.ylo);
    xhi = std::max(xhi, o.xhi);
    yhi = std::max(yhi, o.yhi);
  }
  friend bool operator==(const Rect&, const Rect&) = default;
};

// The distinct x (alongX) or y coordinates of the rects' edges, ascending: the slab and strip
// boundaries of a sweep over them.
inline std::vector<Dbu> edgeCoords(const std::vector<Rect>& rects, bool alongX) {
  std::vector<Dbu> cs;
  cs.reserve(2 * rects.size());
  for (const Rect& r : rects) cs.insert(cs.end(), {alongX ? r.xlo : r.ylo, alongX ? r.xhi : r.yhi});
  std::sort(cs.begin(), cs.end());
  cs.erase(std::unique(cs.begin(), cs.end()), cs.end());
  return cs;
}

// The eight DEF/LEF orientations. N is the identity; FS = mirrored about the
// x axis, FN = mirrored about the y axis, E/W/S rotations counter-clockwise by
// 270/90/180 degrees.
enum class Orient : uint8_t { N, S, E, W, FN, FS, FE, FW };

inline constexpr std::string_view kOrientNames[] = {"N", "S", "E", "W", "FN", "FS", "FE", "FW"};

inline std::string_view orientName(Orient o) { return kOrientNames[static_cast<int>(o)]; }

// Returns false when `s` is not an orientation name.
inline bool parseOrient(std::string_view s, Orient& out) {
  for (int i = 0; i < 8; ++i) {
    if (kOrientNames[i] == s) {
      out = static_cast<Orient>(i);
      return true;
    }
  }
  return false;
}

// Placement of a macro: its local geometry (origin at the macro's lower-left
// corner after the LEF ORIGIN shift) is oriented, then its bounding box of
// size (width, height) is moved so that its lower-left corner sits at `at`.
// This is the DEF COMPONENTS / PINS placement semantic.
struct Transform {
  Point at;                // DBU, lower-left corner of the placed bounding box
  Orient orient = Orient::N;
  Dbu width = 0;           // DBU, macro SIZE x (un-oriented)
  Dbu height = 0;          // DBU, macro SIZE y (un-oriented)

  Point apply(Point p) const {
    const Dbu w = width, h = height;
    Point q;
    switch (orient) {
      case Orient::N: q = {p.x, p.y}; break;
      case Orient::S: q = {w - p.x, h - p.y}; break;
      case Orient::E: q = {p.y, w - p.x}; break;     // rotate 270 deg ccw (90 cw)
      case Orient::W: q = {h - p.y, p.x}; break;     // rotate 90 deg ccw
      case Orient::FN: q = {w - p.x, p.y}; break;
      case Orient::FS: q = {p.x, h - p.y}; break;
      case Orient::FE: q = {p.y, p.x}; break;
      case Orient::FW: q = {h - p.y, w - p.x}; break;
    }
    return {q.x + at.x, q.y + at.y};
  }
  Rect apply(const Rect& r) const {
    return Rect::fromCorners(apply(Point{r.xlo, r.ylo}), apply(Point{r.xhi, r.yhi}));
  }
};

}  // namespace xroute
