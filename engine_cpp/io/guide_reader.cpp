// ISPD global-routing guide reader. The format, per net:
//   <net name>
//   (
//   <xlo> <ylo> <xhi> <yhi> <layer name>
//   ...
//   )
// Coordinates are DEF DBU. Guides end up in flat per-net arrays in DEF net
// order, keeping file order within a net.
#include "io/lexer.hpp"
#include "io/readers.hpp"

namespace xroute {

namespace {

struct GuideRow {
  int32_t net;
  Rect rect;
  LayerId layer;
};

std::string rectText(Dbu x1, Dbu y1, Dbu x2, Dbu y2) {
  return std::to_string(x1) + " " + std::to_string(y1) + " " + std::to_string(x2) + " " + std::to_string(y2);
}

void parseGuides(Lexer& lex, const Tech& tech, Design& design) {
  if (lex.atEnd()) lex.fail(1, "empty guide file (no net)");
  const Rect& die = design.dieArea;
  const bool haveDie = design.dieLine > 0 && die.xhi > die.xlo && die.yhi > die.ylo;
  int partlyOutside = 0;
  int firstPartlyOutside = 0;
  std::vector<GuideRow> rows;
  std::vector<int32_t> perNet(design.nets.size(), 0);
  while (!lex.atEnd()) {
    const Token nameTok = lex.next();
    if (!nameTok.quoted && (nameTok.text == "(" || nameTok.text == ")")) {
      lex.failAt(nameTok, "expected a net name, found " + quoteToken(nameTok.text));
    }
    const NetId net = design.findNet(nameTok.text);
    if (!net.valid()) lex.failAt(nameTok, "net " + quoteToken(nameTok.text) + " is not in the DEF");
    lex.expect("(");
    while (true) {
      const Token& t = lex.peek();
      if (!t.quoted && t.text == ")") {
        lex.next();
        break;
      }
      const Token first = lex.peek();
      const Dbu x1 = lex.dbu();
      const Dbu y1 = lex.dbu();
      const Dbu x2 = lex.dbu();
      const Dbu y2 = lex.dbu();
      const Token layerTok = lex.next();
      const LayerId layer = tech.findLayer(layerTok.text);
      if (!layer.valid()) lex.failAt(layerTok, "unknown layer " + quoteToken(layerTok.text));
      if (tech.layer(layer).type != LayerType::Routing) {
        lex.failAt(layerTok, "guide layer " + quoteToken(layerTok.text) + " is not a routing layer");
      }
      if (x1 > x2 || y1 > y2) {
        lex.failAt(first, "guide rectangle is inverted (" + rectText(x1, y1, x2, y2) +
                              "): the first corner must be the lower left");
      }
      if (x1 == x2 || y1 == y2) {
        lex.failAt(first, "guide rectangle has zero " + std::string(x1 == x2 ? "width" : "height") + " (" +
                              rectText(x1, y1, x2, y2) + ")");
      }
      if (haveDie) {
        if (x2 <= die.xlo || x1 >= die.xhi || y2 <= die.ylo || y1 >= die.yhi) {
          lex.failAt(first, "guide rectangle (" + rectText(x1, y1, x2, y2) + ") lies outside the die area (" +
                                rectText(die.xlo, die.ylo, die.xhi, die.yhi) + ")");
        }
        if (x1 < die.xlo || y1 < die.ylo || x2 > die.xhi || y2 > die.yhi) {
          if (partlyOutside++ == 0) firstPartlyOutside = first.line;
        }
      }
      rows.push_back({*net, Rect::fromCorners({x1, y1}, {x2, y2}), layer});
      ++perNet[*net];
    }
  }
  if (partlyOutside > 0) {
    design.warnings.push_back(lex.path() + ":" + std::to_string(firstPartlyOutside) + ": " +
                              std::to_string(partlyOutside) + " guide rectangle(s) reach past the die area (" +
                              rectText(die.xlo, die.ylo, die.xhi, die.yhi) + "); the first is here");
    ++design.warningCount;
  }
  // Counting sort by net id: stable, so file order is kept within a net.
  design.guideStart.assign(design.nets.size() + 1, 0);
  design.guidesBuiltIn = false;
  for (size_t i = 0; i < perNet.size(); ++i) design.guideStart[i + 1] = design.guideStart[i] + perNet[i];
  design.guideRects.assign(rows.size(), Rect{});
  design.guideLayers.assign(rows.size(), LayerId{});
  std::vector<int32_t> fill(design.guideStart.begin(), design.guideStart.end() - 1);
  for (const GuideRow& r : rows) {
    const int32_t at = fill[r.net]++;
    design.guideRects[at] = r.rect;
    design.guideLayers[at] = r.layer;
  }
}

}  // namespace

// Guides are written in the DEF's units: rescaled as the DEF was (Design::defScaleMul/Div).
void readGuides(const std::string& path, const Tech& tech, Design& design) {
  Lexer lex = Lexer::fromFile(path);
  lex.setScale(design.defScaleMul, design.defScaleDiv);
  parseGuides(lex, tech, design);
}

void readGuidesText(const std::string& name, std::string text, const Tech& tech, Design& design) {
  Lexer lex(name, std::move(text));
  lex.setScale(design.defScaleMul, design.defScaleDiv);
  parseGuides(lex, tech, design);
}

}  // namespace xroute
