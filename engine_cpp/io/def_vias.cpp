// DEF VIAS section: fixed vias (+ RECT / + POLYGON) and vias generated from
// a LEF VIARULE with their parameters (+ CUTSIZE, + LAYERS, + CUTSPACING,
// + ENCLOSURE, + ROWCOL, + ORIGIN, + OFFSET, + PATTERN).
#include "io/def_parser.hpp"

namespace xroute {

namespace {

int hexValue(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

// Expands one row definition ("F0", "R4F", "" = all cuts) into `cols` flags.
bool expandRow(std::string_view def, int cols, std::vector<char>& row, std::string& error) {
  row.assign(cols, def.empty() ? 1 : 0);
  if (def.empty()) return true;
  std::vector<int> digits;
  for (size_t i = 0; i < def.size(); ++i) {
    if (def[i] == 'R' || def[i] == 'r') {
      if (i + 2 >= def.size()) {
        error = "bad repeat in PATTERN row '" + std::string(def) + "'";
        return false;
      }
      const int n = hexValue(def[i + 1]);
      const int d = hexValue(def[i + 2]);
      if (n < 0 || d < 0) {
        error = "bad repeat in PATTERN row '" + std::string(def) + "'";
        return false;
      }
      digits.insert(digits.end(), n, d);
      i += 2;
    } else {
      const int d = hexValue(def[i]);
      if (d < 0) {
        error = "bad hex digit in PATTERN row '" + std::string(def) + "'";
        return false;
      }
      digits.push_back(d);
    }
  }
  // Each hex digit gives 4 cuts, most significant bit first (left to right).
  for (int c = 0; c < cols; ++c) {
    const size_t digit = static_cast<size_t>(c / 4);
    row[c] = digit < digits.size() && (digits[digit] & (8 >> (c % 4))) ? 1 : 0;
  }
  return true;
}

// Cut flags rows x cols (row 0 = bottom) from a PATTERN "n_def_n_def...".
bool expandPattern(const DefVia& v, std::vector<char>& present, std::string& error) {
  present.assign(static_cast<size_t>(v.rows) * v.cols, 1);
  if (v.pattern.empty()) return true;
  present.assign(present.size(), 0);
  std::vector<std::string_view> parts;
  std::string_view s = v.pattern;
  while (true) {
    const size_t u = s.find('_');
    parts.push_back(s.substr(0, u));
    if (u == std::string_view::npos) break;
    s.remove_prefix(u + 1);
  }
  if (parts.size() % 2 != 0) {
    error = "PATTERN '" + v.pattern + "' is not a list of count_row pairs";
    return false;
  }
  int row = 0;
  std::vector<char> flags;
  for (size_t i = 0; i < parts.size(); i += 2) {
    int repeat = 0;
    if (parts[i].empty()) {
      error = "PATTERN '" + v.pattern + "': empty row count";
      return false;
    }
    for (char c : parts[i]) {
      const int d = hexValue(c);
      if (d < 0 || repeat > (1 << 20)) {
        error = "PATTERN '" + v.pattern + "': bad row count";
        return false;
      }
      repeat = repeat * 16 + d;
    }
    if (!expandRow(parts[i + 1], v.cols, flags, error)) return false;
    for (int k = 0; k < repeat && row < v.rows; ++k, ++row) {
      std::copy(flags.begin(), flags.end(), present.begin() + static_cast<size_t>(row) * v.cols);
    }
  }
  return true;
}

}  // namespace

bool generateViaShapes(DefVia& d, std::string& error) {
  Via& via = d.via;
  via.shapes.clear();
  via.bottom = d.botLayer;
  via.cut = d.cutLayer;
  via.top = d.topLayer;
  std::vector<char> present;
  if (!expandPattern(d, present, error)) return false;
  const int64_t w = int64_t(d.cols) * d.cutSizeX + int64_t(d.cols - 1) * d.cutSpacingX;
  const int64_t h = int64_t(d.rows) * d.cutSizeY + int64_t(d.rows - 1) * d.cutSpacingY;
  if (w > 1000000000 || h > 1000000000) {
    error = "generated via is too large";
    return false;
  }
  const Dbu xlo = d.originX - static_cast<Dbu>(w / 2);
  const Dbu ylo = d.originY - static_cast<Dbu>(h / 2);
  const Rect array{xlo, ylo, xlo + static_cast<Dbu>(w), ylo + static_cast<Dbu>(h)};
  const Rect bottom{array.xlo - d.botEncX + d.botOffX, array.ylo - d.botEncY + d.botOffY,
                    array.xhi + d.botEncX + d.botOffX, array.yhi + d.botEncY + d.botOffY};
  const Rect top{array.xlo - d.topEncX + d.topOffX, array.ylo - d.topEncY + d.topOffY,
                 array.xhi + d.topEncX + d.topOffX, array.yhi + d.topEncY + d.topOffY};
  via.shapes.push_back({d.botLayer, bottom});
  for (int r = 0; r < d.rows; ++r) {
    for (int c = 0; c < d.cols; ++c) {
      if (!present[static_cast<size_t>(r) * d.cols + c]) continue;
      const Dbu x = xlo + c * (d.cutSizeX + d.cutSpacingX);
      const Dbu y = ylo + r * (d.cutSizeY + d.cutSpacingY);
      via.shapes.push_back({d.cutLayer, Rect{x, y, x + d.cutSizeX, y + d.cutSizeY}});
    }
  }
  via.shapes.push_back({d.topLayer, top});
  return true;
}

void DefParser::readVias() {
  const int declared = readSectionCount();
  readEntries("VIAS", declared, [&] { readVia(); });
}

void DefParser::readVia() {
  const Token nameTok = entryName("a via name");
  const DefViaId id(static_cast<int32_t>(design_.vias.size()));
  if (!design_.viaIndex.emplace(std::string(nameTok.text), id).second) {
    lex_.failAt(nameTok, "duplicate via " + quoteToken(nameTok.text));
  }
  DefVia v;
  v.via.name = std::string(nameTok.text);
  bool haveShapes = false, haveCutSize = false, haveLayers = false;
  int ruleLine = 0;
  for (Token kw; nextOption(kw);) {
    const std::string_view k = kw.quoted ? std::string_view() : kw.text;
    if (k == "RECT" || k == "POLYGON") {
      v.via.shapes.push_back(readViaShape(kw));
      haveShapes = true;
    } else if (k == "VIARULE") {
      const Token ruleTok = lex_.next();
      v.rule = tech_.findViaRule(ruleTok.text);
      if (!v.rule.valid()) lex_.failAt(ruleTok, "unknown via rule " + quoteToken(ruleTok.text));
      v.generated = true;
      ruleLine = kw.line;
    } else if (k == "CUTSIZE") {
      v.cutSizeX = lex_.dbu();
      v.cutSizeY = lex_.dbu();
      haveCutSize = true;
    } else if (k == "LAYERS") {
      readViaLayers(v);
      haveLayers = true;
    } else if (k == "CUTSPACING") {
      v.cutSpacingX = lex_.dbu();
      v.cutSpacingY = lex_.dbu();
    } else if (k == "ENCLOSURE") {
      v.botEncX = lex_.dbu();
      v.botEncY = lex_.dbu();
      v.topEncX = lex_.dbu();
      v.topEncY = lex_.dbu();
    } else if (k == "ROWCOL") {
      const Token rt = lex_.peek();
      const int64_t rows = lex_.integer();
      const int64_t cols = lex_.integer();
      if (rows < 1 || cols < 1 || rows * cols > 1000000) lex_.failAt(rt, "bad ROWCOL");
      v.rows = static_cast<int>(rows);
      v.cols = static_cast<int>(cols);
    } else if (k == "ORIGIN") {
      v.originX = lex_.dbu();
      v.originY = lex_.dbu();
    } else if (k == "OFFSET") {
      v.botOffX = lex_.dbu();
      v.botOffY = lex_.dbu();
      v.topOffX = lex_.dbu();
      v.topOffY = lex_.dbu();
    } else if (k == "PATTERN") {
      v.pattern = readViaPattern();
    } else if (k.empty() || k == ";") {
      unexpected(kw, "a via option");
    } else {
      skipToOptionEnd();
      countSkip("VIAS." + std::string(k));
    }
  }
  if (v.generated && haveShapes) lex_.fail(ruleLine, "via " + quoteToken(v.via.name) + " has both VIARULE and RECT");
  if (v.generated && (!haveCutSize || !haveLayers)) {
    lex_.fail(ruleLine, "via " + quoteToken(v.via.name) + " needs + CUTSIZE and + LAYERS with its VIARULE");
  }
  finishVia(v, ruleLine);
  design_.vias.push_back(std::move(v));
}

// "+ PATTERN 2_F0_2_F" as written; some routers quote it ("...", or '...' as one word): the
// quotes are dropped.
std::string DefParser::readViaPattern() {
  const Token t = lex_.next();
  std::string_view p = t.text;
  if (!t.quoted && p.size() >= 2 && p.front() == '\'' && p.back() == '\'') p = p.substr(1, p.size() - 2);
  if (p.empty() || is(t, ";") || is(t, "+")) unexpected(t, "a cut pattern");
  return std::string(p);
}

// "+ LAYERS bottom cut top". Some writers put the cut last ("metal4 metal5 via4", OpenROAD's dpl
// tests): the cut is found by its type and the metals ordered as the LEF orders them.
void DefParser::readViaLayers(DefVia& v) {
  Token toks[3] = {lex_.next(), lex_.next(), lex_.next()};
  LayerId ids[3];
  int cuts = 0;
  for (int i = 0; i < 3; ++i) {
    ids[i] = layerAt(toks[i]);
    if (tech_.layer(ids[i]).type == LayerType::Cut) {
      v.cutLayer = ids[i];
      ++cuts;
    }
  }
  if (cuts != 1) lex_.failAt(toks[1], "+ LAYERS needs one cut layer and two routing layers");
  const bool cutMiddle = ids[1] == v.cutLayer;
  const LayerId a = cutMiddle ? ids[0] : (ids[0] == v.cutLayer ? ids[1] : ids[0]);
  const LayerId b = cutMiddle ? ids[2] : (ids[2] == v.cutLayer ? ids[1] : ids[2]);
  for (const Token& t : toks) {
    if (tech_.layer(layerAt(t)).type != LayerType::Cut) routingLayerAt(t);
  }
  v.botLayer = cutMiddle ? a : std::min(a, b);
  v.topLayer = cutMiddle ? b : std::max(a, b);
}

// + RECT layer pt pt  |  + POLYGON layer pt pt pt ... (kept as its bounding box, counted), with an
// optional + MASK n after the layer (skipped, counted).
ViaShape DefParser::readViaShape(const Token& kw) {
  const LayerId layer = layerAt(lex_.next());
  if (lex_.accept("+")) {
    lex_.expect("MASK");
    const Token v = lex_.peek();
    checkMask(v, lex_.integer(), false);
    countSkip("VIAS.MASK");
  }
  if (kw.text == "RECT") {
    const int line = lex_.peek().line;
    const Point a = readPoint();
    const Point b = readPoint();
    checkCorners(line, a, b, "via RECT");
    return {layer, Rect::fromCorners(a, b)};
  }
  const std::vector<Point> pts = readPolygonPoints(kw);
  Rect r{pts[0].x, pts[0].y, pts[0].x, pts[0].y};
  for (const Point& p : pts) r.expandToInclude(Rect{p.x, p.y, p.x, p.y});
  countSkip("VIAS.POLYGON");
  ++design_.warningCount;
  return {layer, r};
}

// A generated via gets its shapes from its rule; a fixed one its bottom/top (the lowest and
// highest routing layers, LEF order) and cut layer from its shapes.
void DefParser::finishVia(DefVia& v, int ruleLine) {
  if (v.generated) {
    std::string error;
    if (!generateViaShapes(v, error)) lex_.fail(ruleLine, "via " + quoteToken(v.via.name) + ": " + error);
    return;
  }
  for (const ViaShape& s : v.via.shapes) {
    const Layer& l = tech_.layer(s.layer);
    if (l.type == LayerType::Cut) {
      if (!v.via.cut.valid()) v.via.cut = s.layer;
    } else if (l.type == LayerType::Routing) {
      if (!v.via.bottom.valid() || *s.layer < *v.via.bottom) v.via.bottom = s.layer;
      if (!v.via.top.valid() || *s.layer > *v.via.top) v.via.top = s.layer;
    }
  }
}

}  // namespace xroute
