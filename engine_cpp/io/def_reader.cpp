// DEF reader: header statements, DIEAREA, ROW, TRACKS, GCELLGRID,
// COMPONENTS, BLOCKAGES, and the sections we skip. PINS are in
// def_pins.cpp, VIAS in def_vias.cpp, NETS and SPECIALNETS in def_nets.cpp.
//
// Coordinates are DEF integers (DBU) as written. Anything legal that we do
// not keep is skipped and counted in Design::skippedStatements under
// "SECTION.KEYWORD" (e.g. "COMPONENTS.SOURCE"; a skipped section counts
// under its own name); anything malformed or unknown throws InputError with
// the offending token's line.
//
// Decisions (also in the report of the DEF task):
// - A PINS entry whose + NET names a net that NETS lacks is allowed: netName
//   is kept, IoPin::net stays invalid.
// - UNITS that differ from the LEF's DATABASE MICRONS by an integer ratio
//   rescale every coordinate to the LEF's units (warned); others are an error.
// - A section count that differs from its entries is a warning, as in OpenROAD.
// - Kept approximately (counted and warned): POLYGONs of pins, vias and
//   special nets (their bounding box); a pin's ports with different
//   placements (shapes made absolute, placement dropped); via orientations
//   other than N (ignored). Kept as ROUTED: FIXED/COVER/NOSHIELD/SHIELD
//   wiring. A TAPER segment of regular wiring gets the layer's default width
//   (a NONDEFAULTRULE's width everywhere else on its net). Not kept: MASK, STYLE,
//   TAPERRULE, VIRTUAL, wildcard "( * pin )" refs in NETS, component
//   SOURCE/WEIGHT/HALO..., blockage options.
#include <algorithm>
#include <limits>

#include "io/def_parser.hpp"
#include "io/readers.hpp"

namespace xroute {

namespace {

// Sections we do not use: skipped up to "END <keyword>" and counted.
constexpr std::string_view kSkippedSections[] = {
    "PROPERTYDEFINITIONS", "REGIONS", "GROUPS", "FILLS", "SCANCHAINS",
    "SLOTS", "PINPROPERTIES", "IOTIMINGS", "FLOORPLANCONSTRAINTS", "TIMINGDISABLES",
    "CONSTRAINTS", "ASSERTIONS"};

// Statements "KEYWORD ... ;" we do not use.
constexpr std::string_view kSkippedStatements[] = {"TECHNOLOGY", "HISTORY", "NAMESCASESENSITIVE",
                                                    "NAMEMAPSTRINGS", "COMPONENTMASKSHIFT"};

// Far above any real design (ISPD 2019's largest: about 20,000 tracks and 600 GCell lines per
// axis), low enough that the grids built from them fit in memory.
constexpr int64_t kMaxTracks = 10000000;
constexpr int64_t kMaxGCellLines = 1000000;

template <size_t N>
bool contains(const std::string_view (&list)[N], std::string_view w) {
  return std::find(std::begin(list), std::end(list), w) != std::end(list);
}

}  // namespace

// ---------------------------------------------------------------------------
// Helpers

void DefParser::countSkip(std::string_view key, int n) {
  for (auto& [k, v] : design_.skippedStatements) {
    if (k == key) {
      v += n;
      return;
    }
  }
  design_.skippedStatements.emplace_back(std::string(key), n);
}

bool DefParser::nextOption(Token& kw) {
  const Token t = lex_.next();
  if (is(t, ";")) return false;
  if (!is(t, "+")) unexpected(t, "'+' or ';'");
  kw = lex_.next();
  lex_.upcase(kw);
  return true;
}

void DefParser::unexpected(const Token& t, const std::string& expected) const {
  lex_.failAt(t, "expected " + expected + ", found " + (t.quoted ? "the quoted string " : "") + quoteToken(t.text));
}

Point DefParser::readPoint() {
  lex_.expect("(");
  const Dbu x = lex_.dbu();
  const Dbu y = lex_.dbu();
  lex_.expect(")");
  return {x, y};
}

std::vector<Point> DefParser::readPolygonPoints(const Token& kw) {
  std::vector<Point> pts;
  while (peekIs("(")) {
    lex_.next();
    Point p;
    for (Dbu* v : {&p.x, &p.y}) {
      if (peekIs("*")) {  // "*": the previous point's coordinate
        const Token star = lex_.next();
        if (pts.empty()) lex_.failAt(star, "'*' in the first point of a POLYGON");
        *v = v == &p.x ? pts.back().x : pts.back().y;
      } else {
        *v = lex_.dbu();
      }
    }
    lex_.expect(")");
    pts.push_back(p);
  }
  if (pts.size() < 3) lex_.failAt(kw, "POLYGON needs at least 3 points");
  return pts;
}

LayerId DefParser::layerAt(const Token& t) const {
  const LayerId id = tech_.findLayer(t.text);
  if (!id.valid() || t.quoted) lex_.failAt(t, "unknown layer " + quoteToken(t.text));
  return id;
}

LayerId DefParser::routingLayerAt(const Token& t) const {
  const LayerId id = layerAt(t);
  if (tech_.layer(id).type != LayerType::Routing) {
    lex_.failAt(t, "layer " + quoteToken(t.text) + " is not a routing layer");
  }
  return id;
}

ViaRef DefParser::findVia(std::string_view name) const {
  auto it = design_.viaIndex.find(name);
  if (it != design_.viaIndex.end()) return ViaRef{*it->second, true};
  const ViaId id = tech_.findVia(name);
  return id.valid() ? ViaRef{*id, false} : ViaRef{};
}

Orient DefParser::orientAt(const Token& t) const {
  Orient o = Orient::N;
  if (t.quoted || !parseOrient(t.text, o)) lex_.failAt(t, "bad orientation " + quoteToken(t.text));
  return o;
}

PlaceStatus DefParser::readPlacement(const Token& kw, Point& at, Orient& orient) {
  at = readPoint();
  orient = orientAt(lex_.next());
  if (kw.text == "FIXED") return PlaceStatus::Fixed;
  if (kw.text == "COVER") return PlaceStatus::Cover;
  return PlaceStatus::Placed;
}

int DefParser::readSectionCount() {
  const Token t = lex_.peek();
  const int64_t n = lex_.integer();
  if (n < 0 || n > std::numeric_limits<int>::max()) lex_.failAt(t, "bad section count " + quoteToken(t.text));
  lex_.expect(";");
  return static_cast<int>(n);
}

bool DefParser::atSectionEnd(std::string_view section, int declared, int found) {
  const Token& t = lex_.peek();
  if (is(t, "-")) return false;
  if (!is(t, "END")) unexpected(t, "'-' or 'END " + std::string(section) + "'");
  const Token end = lex_.next();
  lex_.expect(section);
  if (declared != found) {  // OpenROAD and the Si2 parser warn and go on
    warn(end.line, std::string(section) + " " + std::to_string(declared) + " declared, " + std::to_string(found) +
                       " found");
  }
  return true;
}

void DefParser::warn(int line, const std::string& message) {
  design_.warnings.push_back(lex_.path() + ":" + std::to_string(line) + ": " + message);
  ++design_.warningCount;
}

Token DefParser::entryName(std::string_view what) {
  const Token t = lex_.next();
  if (is(t, ";") || t.quoted) unexpected(t, std::string(what));
  return t;
}

std::string DefParser::quotedChars(size_t count, const std::string& what) {
  const Token t = lex_.next();
  bool ok = t.quoted && t.text.size() == count;
  for (char c : t.text) ok = ok && c > ' ' && c < 127 && c != '"' && c != '\\';
  if (!ok) lex_.failAt(t, "expected " + what + " in double quotes, found " + quoteToken(t.text));
  return std::string(t.text);
}

std::string DefParser::plainWord(const std::string& what) {
  if (!lex_.atEnd() && lex_.peek().quoted) unexpected(lex_.peek(), what);
  return lex_.word(what);
}

void DefParser::skipToOptionEnd() {
  while (true) {
    const Token& t = lex_.peek();
    if (is(t, "+") || is(t, ";")) return;
    lex_.next();
  }
}

void DefParser::skipSection(std::string_view keyword) {
  const bool ext = keyword == "BEGINEXT";
  while (true) {
    const Token t = lex_.next();
    if (ext ? is(t, "ENDEXT") : (is(t, "END") && peekIs(keyword))) {
      if (!ext) lex_.next();
      break;
    }
  }
  countSkip(keyword);
}

// ---------------------------------------------------------------------------
// Top level

void DefParser::parse() {
  design_.netPinStart.assign(1, 0);
  bool ended = false;
  bool named = false;
  while (!lex_.atEnd()) {
    const Token t = lex_.next();
    if (t.quoted) unexpected(t, "a DEF statement");
    std::string upper(t.text);  // keywords are case-insensitive; an error still quotes what was written
    for (char& c : upper) c = (c >= 'a' && c <= 'z') ? static_cast<char>(c - 'a' + 'A') : c;
    const std::string_view k = upper;
    lex_.noteKeyword(t);
    if (k == "END") {
      design_.endLine = t.line;
      lex_.expect("DESIGN");
      if (!named) lex_.failAt(t, "missing DESIGN statement before END DESIGN");
      ended = true;
      break;
    } else if (k == "VERSION") {
      design_.version = lex_.word("a version number");
      lex_.expect(";");
    } else if (k == "DIVIDERCHAR") {
      design_.dividerChar = quotedChars(1, "a divider character");
      lex_.expect(";");
    } else if (k == "BUSBITCHARS") {
      design_.busBitChars = quotedChars(2, "bus bit characters");
      lex_.expect(";");
    } else if (k == "DESIGN") {
      design_.name = plainWord("a design name");
      named = true;
      lex_.expect(";");
    } else if (k == "UNITS") {
      readUnits();
    } else if (k == "DIEAREA") {
      readDieArea();
    } else if (k == "ROW") {
      readRow();
    } else if (k == "TRACKS") {
      readTracks();
    } else if (k == "GCELLGRID") {
      readGCellGrid();
    } else if (k == "VIAS") {
      readVias();
    } else if (k == "COMPONENTS") {
      readComponents();
    } else if (k == "PINS") {
      readPins();
    } else if (k == "BLOCKAGES") {
      readBlockages();
    } else if (k == "SPECIALNETS") {
      readSpecialNets();
    } else if (k == "NETS") {
      readNets();
    } else if (k == "NONDEFAULTRULES") {
      readNonDefaultRules();
    } else if (k == "STYLES") {
      readStyles();
    } else if (k.starts_with("&DEFINE")) {  // &defines / &defineS / &defineB: "&defineX &name = value ;"
      lex_.skipStatement();
      countSkip(k);
      warn(t.line, std::string(k) + " skipped: its variables are not expanded");
    } else if (contains(kSkippedStatements, k)) {
      lex_.skipStatement();
      countSkip(k);
    } else if (contains(kSkippedSections, k) || k == "BEGINEXT") {
      skipSection(k);
    } else {
      unexpected(t, "a DEF statement");
    }
  }
  if (!ended) lex_.fail(lex_.line(), "unexpected end of file: missing 'END DESIGN'");
  if (!lex_.atEnd()) {
    const Token& t = lex_.peek();
    lex_.failAt(t, "unexpected text after END DESIGN: " + quoteToken(t.text));
  }
  resolveIoPinNets();
  flushTally();
}

void DefParser::readUnits() {
  lex_.expect("DISTANCE");
  lex_.expect("MICRONS");
  const Token t = lex_.peek();
  const int64_t n = lex_.integer();
  if (n <= 0 || n > 1000000) lex_.failAt(t, "bad DEF database units " + quoteToken(t.text));
  design_.dbuPerMicron = static_cast<int>(n);
  const int lef = tech_.dbuPerMicron;
  if (lef != 0 && n != lef) {
    // Coordinates are kept in the LEF's units: an integer ratio either way rescales them.
    const std::string both = "DEF UNITS DISTANCE MICRONS " + std::to_string(n) + " and the LEF's DATABASE MICRONS " +
                             std::to_string(lef);
    if (lef % n == 0) {
      lex_.setScale(static_cast<int>(lef / n), 1);
    } else if (n % lef == 0) {
      lex_.setScale(1, static_cast<int>(n / lef));
    } else {
      lex_.failAt(t, both + " have no integer ratio: the coordinates cannot be rescaled exactly");
    }
    warn(t.line, both + " differ: DEF coordinates rescaled to the LEF's units");
    design_.defScaleMul = lex_.scaleMul();
    design_.defScaleDiv = lex_.scaleDiv();
    design_.dbuPerMicron = lef;
  }
  lex_.expect(";");
}

void DefParser::readDieArea() {
  const int line = lex_.line();
  std::vector<Point> pts;
  while (!peekIs(";")) pts.push_back(readPoint());
  lex_.next();
  if (pts.size() < 2) lex_.fail(line, "DIEAREA needs at least 2 points");
  if (design_.dieLine > 0) lex_.fail(line, "second DIEAREA (the first is at line " + std::to_string(design_.dieLine) + ")");
  if (pts.size() == 2 && (pts[0].x > pts[1].x || pts[0].y > pts[1].y)) {
    lex_.fail(line, "DIEAREA corners are inverted: the first point must be the lower left (" +
                        std::to_string(pts[0].x) + " " + std::to_string(pts[0].y) + " is above or right of " +
                        std::to_string(pts[1].x) + " " + std::to_string(pts[1].y) + ")");
  }
  Rect box = Rect::fromCorners(pts[0], pts[1]);
  for (const Point& p : pts) box.expandToInclude(Rect{p.x, p.y, p.x, p.y});
  if (box == Rect{0, 0, 0, 0}) {  // "( 0 0 ) ( 0 0 )": what OpenROAD writes for an unset die; as if absent
    warn(line, "DIEAREA ( 0 0 ) ( 0 0 ): read as no DIEAREA");
    return;
  }
  if (box.xhi <= box.xlo || box.yhi <= box.ylo) {
    lex_.fail(line, "DIEAREA has zero " + std::string(box.xhi <= box.xlo ? "width" : "height") + " (" +
                        std::to_string(box.xlo) + " " + std::to_string(box.ylo) + " to " + std::to_string(box.xhi) +
                        " " + std::to_string(box.yhi) + ")");
  }
  design_.dieLine = line;
  design_.dieArea = box;
  design_.diePolygon = std::move(pts);
}

void DefParser::readRow() {
  Row row;
  row.name = plainWord("a row name");
  const Token site = lex_.next();
  if (is(site, ";") || tech_.siteIndex.find(site.text) == tech_.siteIndex.end()) {
    lex_.failAt(site, "unknown site " + quoteToken(site.text));
  }
  row.site = std::string(site.text);
  row.origin.x = lex_.dbu();
  row.origin.y = lex_.dbu();
  row.orient = orientAt(lex_.next());
  if (lex_.accept("DO")) {
    const Token nx = lex_.peek();
    const int64_t x = lex_.integer();
    lex_.expect("BY");
    const int64_t y = lex_.integer();
    if (x < 1 || y < 1 || x > 1000000000 || y > 1000000000) lex_.failAt(nx, "bad ROW repeat count");
    row.numX = static_cast<int>(x);
    row.numY = static_cast<int>(y);
    if (lex_.accept("STEP")) {
      row.stepX = lex_.dbu();
      row.stepY = lex_.dbu();
    }
    if (!withinDbuRange(row.origin.x + int64_t(row.stepX) * (x - 1)) ||
        !withinDbuRange(row.origin.y + int64_t(row.stepY) * (y - 1))) {
      lex_.failAt(nx, "ROW runs beyond the engine's range, " + dbuRangeText());
    }
  }
  while (lex_.accept("+")) {
    const Token kw = lex_.next();
    lex_.upcase(kw);
    if (!is(kw, "PROPERTY")) unexpected(kw, "PROPERTY or ';'");
    skipToOptionEnd();
    countSkip("ROW.PROPERTY");
  }
  lex_.expect(";");
  design_.rows.push_back(std::move(row));
}

void DefParser::readTracks() {
  const Token axis = lex_.next();
  if (!is(axis, "X") && !is(axis, "Y")) unexpected(axis, "X or Y");
  TrackPattern pat;
  pat.isX = axis.text == "X";
  pat.line = axis.line;
  pat.start = lex_.dbu();
  lex_.expect("DO");
  const Token countTok = lex_.peek();
  const int64_t count = lex_.integer();
  if (count < 1 || count > kMaxTracks) {
    lex_.failAt(countTok, "bad track count " + quoteToken(countTok.text) + " (1.." + std::to_string(kMaxTracks) + ")");
  }
  pat.count = static_cast<int>(count);
  lex_.expect("STEP");
  const Token stepTok = lex_.peek();
  pat.step = lex_.dbu();
  if (pat.step <= 0) lex_.failAt(stepTok, "TRACKS STEP must be positive, found " + quoteToken(stepTok.text));
  if (!withinDbuRange(static_cast<int64_t>(pat.start) + static_cast<int64_t>(pat.step) * (pat.count - 1))) {
    lex_.failAt(stepTok, "TRACKS run beyond the engine's range, " + dbuRangeText());
  }
  if (lex_.accept("MASK")) {
    lex_.integer();
    lex_.accept("SAMEMASK");
    countSkip("TRACKS.MASK");
  }
  int layers = 0;
  if (lex_.accept("LAYER")) {
    while (!peekIs(";")) {
      pat.layer = layerAt(lex_.next());
      design_.tracks.push_back(pat);
      ++layers;
    }
  }
  const Token semi = lex_.next();
  // Without LAYER the tracks belong to no layer; OpenROAD reads such a statement and keeps nothing.
  if (layers == 0) warn(semi.line, "TRACKS without a LAYER: ignored");
}

void DefParser::readGCellGrid() {
  const Token axis = lex_.next();
  if (!is(axis, "X") && !is(axis, "Y")) unexpected(axis, "X or Y");
  GCellPattern g;
  g.isX = axis.text == "X";
  if (design_.gcellLine == 0) design_.gcellLine = axis.line;
  g.start = lex_.dbu();
  lex_.expect("DO");
  const Token countTok = lex_.peek();
  const int64_t count = lex_.integer();
  if (count < 1 || count > kMaxGCellLines) {
    lex_.failAt(countTok, "bad GCELLGRID count " + quoteToken(countTok.text) + " (1.." + std::to_string(kMaxGCellLines) + ")");
  }
  g.count = static_cast<int>(count);
  lex_.expect("STEP");
  const Token stepTok = lex_.peek();
  g.step = lex_.dbu();
  if (g.step <= 0) lex_.failAt(stepTok, "GCELLGRID STEP must be positive, found " + quoteToken(stepTok.text));
  if (!withinDbuRange(static_cast<int64_t>(g.start) + static_cast<int64_t>(g.step) * (g.count - 1))) {
    lex_.failAt(stepTok, "GCELLGRID runs beyond the engine's range, " + dbuRangeText());
  }
  lex_.expect(";");
  design_.gcellGrid.push_back(g);
}

// ---------------------------------------------------------------------------
// COMPONENTS

void DefParser::readComponents() {
  const int declared = readSectionCount();
  design_.components.reserve(design_.components.size() + saneReserve(declared));
  design_.compIndex.reserve(design_.compIndex.size() + saneReserve(declared));
  readEntries("COMPONENTS", declared, [&] { readComponent(); });
}

void DefParser::readComponent() {
  const Token nameTok = entryName("a component name");
  const Token macroTok = lex_.next();
  const MacroId macro = tech_.findMacro(macroTok.text);
  if (!macro.valid() || macroTok.quoted) lex_.failAt(macroTok, "unknown macro " + quoteToken(macroTok.text));
  const CompId id(static_cast<int32_t>(design_.components.size()));
  if (!design_.compIndex.emplace(std::string(nameTok.text), id).second) {
    lex_.failAt(nameTok, "duplicate component " + quoteToken(nameTok.text));
  }
  Component& c = design_.components.emplace_back();
  c.name = std::string(nameTok.text);
  c.macro = macro;
  for (Token kw; nextOption(kw);) {
    if (is(kw, "PLACED") || is(kw, "FIXED") || is(kw, "COVER")) {
      c.status = readPlacement(kw, c.location, c.orient);
      const Macro& m = tech_.macros[*macro];
      const Transform t{c.location, c.orient, m.width, m.height};
      requireInRange(kw.line, t.apply(Rect{0, 0, m.width, m.height}), "placed component");
      requireMacroShapesInRange(kw.line, c, t);
    } else if (is(kw, "UNPLACED")) {
      c.status = PlaceStatus::Unplaced;
    } else if (is(kw, ";")) {
      unexpected(kw, "a component option");
    } else {
      skipToOptionEnd();
      countSkip("COMPONENTS." + std::string(kw.text));
    }
  }
}

void DefParser::requireMacroShapesInRange(int line, const Component& c, const Transform& t) {
  if (macroShapeBox_.size() != tech_.macros.size()) macroShapeBox_.assign(tech_.macros.size(), std::nullopt);
  std::optional<Rect>& box = macroShapeBox_[*c.macro];
  if (!box) {
    const Macro& m = tech_.macros[*c.macro];
    Rect b{0, 0, 0, 0};  // the SIZE box's corner: already checked, so never a false alarm
    auto add = [&](const MacroShape& s) {
      if (s.polygon.empty()) b.expandToInclude(s.rect);
      for (const Point& p : s.polygon) b.expandToInclude(Rect{p.x, p.y, p.x, p.y});
    };
    for (const MacroPin& pin : m.pins)
      for (const MacroShape& s : pin.shapes) add(s);
    for (const MacroShape& s : m.obstructions) add(s);
    box = b;
  }
  const Rect r = t.apply(*box);  // LEF values and the location are each within kMaxDbu: the sums fit
  if (withinDbuRange(r.xlo) && withinDbuRange(r.ylo) && withinDbuRange(r.xhi) && withinDbuRange(r.yhi)) return;
  lex_.fail(line, "component " + quoteToken(c.name) + " of macro " + quoteToken(tech_.macros[*c.macro].name) +
                      ": its pin and OBS shapes placed here span (" + std::to_string(r.xlo) + " " +
                      std::to_string(r.ylo) + " " + std::to_string(r.xhi) + " " + std::to_string(r.yhi) +
                      "), beyond the engine's range, " + dbuRangeText());
}

// ---------------------------------------------------------------------------
// BLOCKAGES

void DefParser::readBlockages() {
  const int declared = readSectionCount();
  readEntries("BLOCKAGES", declared, [&] { readBlockage(); });
}

void DefParser::readBlockage() {
  Blockage b;
  const Token kind = lex_.next();
  if (is(kind, "LAYER")) {
    b.layer = layerAt(lex_.next());
  } else if (is(kind, "PLACEMENT")) {
    b.placement = true;
  } else {
    unexpected(kind, "LAYER or PLACEMENT");
  }
  while (true) {
    const Token t = lex_.next();
    if (is(t, ";")) break;
    if (is(t, "+")) {
      const Token kw = lex_.next();
      lex_.upcase(kw);
      if (is(kw, "COMPONENT") || is(kw, "SPACING") || is(kw, "DESIGNRULEWIDTH") || is(kw, "MASK") ||
          is(kw, "PARTIAL")) {
        lex_.next();
      } else if (!(is(kw, "PUSHDOWN") || is(kw, "EXCEPTPGNET") || is(kw, "SLOTS") || is(kw, "FILLS") ||
                   is(kw, "SOFT"))) {
        unexpected(kw, "a blockage option");
      }
      countSkip("BLOCKAGES." + std::string(kw.text));
    } else if (is(t, "RECT")) {
      const Point a = readPoint();
      const Point c = readPoint();
      checkCorners(t.line, a, c, "BLOCKAGES RECT");
      b.rects.push_back(Rect::fromCorners(a, c));
    } else if (is(t, "POLYGON")) {
      b.polygons.push_back(readPolygonPoints(t));
    } else {
      unexpected(t, "RECT, POLYGON, '+' or ';'");
    }
  }
  design_.blockages.push_back(std::move(b));
}

// ---------------------------------------------------------------------------
// Entry points

void readDef(const std::string& path, const Tech& tech, Design& design) {
  Lexer lex = Lexer::fromFile(path);
  design.path = path;
  DefParser(lex, tech, design).parse();
}

void readDefText(const std::string& name, std::string text, const Tech& tech, Design& design) {
  Lexer lex(name, std::move(text));
  design.path = name;
  DefParser(lex, tech, design).parse();
}

}  // namespace xroute
