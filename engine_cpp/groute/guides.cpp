#include "groute/guides.hpp"

#include <algorithm>
#include <map>
#include <tuple>

namespace xroute {

namespace {

struct GuideRow {
  int z;
  Rect r;
  friend bool operator<(const GuideRow& a, const GuideRow& b) {
    return std::tie(a.z, a.r.ylo, a.r.xlo, a.r.yhi, a.r.xhi) < std::tie(b.z, b.r.ylo, b.r.xlo, b.r.yhi, b.r.xhi);
  }
  friend bool operator==(const GuideRow& a, const GuideRow& b) { return a.z == b.z && a.r == b.r; }
};

}  // namespace

GuideSet makeGuides(const GrGrid& grid, const std::vector<GrNet>& nets, const LayerAssignment& la, int slack) {
  GuideSet g;
  const int nx = grid.nx(), ny = grid.ny(), nz = grid.nz();
  g.start.push_back(0);
  std::vector<GuideRow> rows;
  auto cellRect = [&](int32_t a, int32_t b) {
    const int x0 = std::max(0, a % nx - slack), y0 = std::max(0, a / nx - slack);
    const int x1 = std::min(nx - 1, b % nx + slack), y1 = std::min(ny - 1, b / nx + slack);
    return Rect{grid.gcells.xs[x0], grid.gcells.ys[y0], grid.gcells.xs[x1 + 1], grid.gcells.ys[y1 + 1]};
  };
  for (size_t n = 0; n < nets.size(); ++n) {
    rows.clear();
    const GrNet& net = nets[n];
    const std::vector<GrSegment>& segs = la.segments[n];
    // Via stacks: GCell -> (lowest, highest) layer attached, and the same from pin layers only for the via count.
    std::map<int32_t, std::pair<int, int>> stack, viaStack;
    auto attach = [](std::map<int32_t, std::pair<int, int>>& m, int32_t c, int zlo, int zhi) {
      auto [it, fresh] = m.try_emplace(c, zlo, zhi);
      if (!fresh) {
        it->second.first = std::min(it->second.first, zlo);
        it->second.second = std::max(it->second.second, zhi);
      }
    };
    for (const GrPin& p : net.pins) {
      attach(stack, p.anchor, p.z, std::min(p.z + 1, nz - 1));
      attach(viaStack, p.anchor, p.z, p.z);
      for (int32_t c : p.cover) {
        for (int z = p.z; z <= std::min(p.z + 1, nz - 1); ++z) rows.push_back({z, cellRect(c, c)});
      }
    }
    for (const GrSegment& s : segs) {
      rows.push_back({s.z, cellRect(s.a, s.b)});
      const int32_t step = s.horizontal ? 1 : nx;
      for (int32_t c = s.a; c <= s.b; c += step) {
        if (c == s.a || c == s.b || stack.count(c)) {
          attach(stack, c, s.z, s.z);
          attach(viaStack, c, s.z, s.z);
        }
      }
    }
    for (const auto& [c, range] : stack) {
      for (int z = range.first; z <= range.second; ++z) rows.push_back({z, cellRect(c, c)});
    }
    for (const auto& [c, range] : viaStack) g.vias += range.second - range.first;
    std::sort(rows.begin(), rows.end());
    rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
    for (const GuideRow& r : rows) {
      g.rects.push_back(r.r);
      g.layers.push_back(grid.layers[r.z].layer);
    }
    g.start.push_back(static_cast<int32_t>(g.rects.size()));
  }
  return g;
}

void installGuides(Design& design, const GuideSet& g) {
  design.guideStart = g.start;
  design.guideRects = g.rects;
  design.guideLayers = g.layers;
  design.guidesBuiltIn = true;
}

std::string guideText(const Tech& tech, const Design& design, const GuideSet& g) {
  std::string out;
  out.reserve(g.rects.size() * 40);
  for (size_t n = 0; n + 1 < g.start.size(); ++n) {
    if (g.start[n] == g.start[n + 1]) continue;
    out += design.nets[n].name;
    out += "\n(\n";
    for (int32_t i = g.start[n]; i < g.start[n + 1]; ++i) {
      const Rect& r = g.rects[i];
      out += std::to_string(r.xlo) + ' ' + std::to_string(r.ylo) + ' ' + std::to_string(r.xhi) + ' ' +
             std::to_string(r.yhi) + ' ' + tech.layer(g.layers[i]).name + '\n';
    }
    out += ")\n";
  }
  return out;
}

}  // namespace xroute
