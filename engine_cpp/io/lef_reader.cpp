// LEF reader: entry points, token helpers, the file-level statements (VERSION,
// BUSBITCHARS, DIVIDERCHAR, UNITS, MANUFACTURINGGRID, CLEARANCEMEASURE,
// PROPERTYDEFINITIONS, END LIBRARY), SITE, and the blocks that are skipped
// whole (top-level SPACING, ARRAY, NOISETABLE, CORRECTIONTABLE, IRDROP, BEGINEXT). The other
// blocks live in lef_layer.cpp, lef58.cpp, lef_via.cpp and lef_macro.cpp.
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>

#include "io/lef_parser.hpp"
#include "io/readers.hpp"

namespace xroute {

bool isNumberText(std::string_view text) {
  const char* b = text.data();
  const char* e = b + text.size();
  if (b != e && *b == '+') ++b;
  if (b == e) return false;
  // from_chars also takes "inf" and "nan": those are names, not numbers.
  const char c = *b == '-' && b + 1 != e ? b[1] : *b;
  if (!(std::isdigit(static_cast<unsigned char>(c)) || c == '.')) return false;
  double v = 0;
  auto [p, ec] = std::from_chars(b, e, v);
  return ec == std::errc() && p == e;
}

LefParser::LefParser(Lexer& lex, Tech& tech) : lex_(lex), tech_(tech) {
  for (size_t i = 0; i < tech_.skippedStatements.size(); ++i) {
    skippedIndex_.emplace(tech_.skippedStatements[i].first, i);
  }
}

// ---------------------------------------------------------------- tokens --

void LefParser::failAt(const Token& t, const std::string& message) const { lex_.failAt(t, message); }

void LefParser::failEof() const {
  std::string msg = "unexpected end of file";
  if (!open_.empty()) {
    const OpenBlock& b = open_.back();
    msg += " inside " + std::string(b.kind) + (b.name.empty() ? "" : " " + quoteToken(b.name)) +
           " (opened at line " + std::to_string(b.line) + ")";
  }
  lex_.fail(lex_.line(), msg);
}

Token LefParser::next() {
  if (lex_.atEnd()) failEof();
  return lex_.next();
}

const Token& LefParser::peek() {
  if (lex_.atEnd()) failEof();
  return lex_.peek();
}

bool LefParser::peekIs(std::string_view word) {
  const Token& t = peek();
  return !t.quoted && isKeyword(t.text, word);
}

bool LefParser::accept(std::string_view word) {
  if (lex_.atEnd()) failEof();
  return lex_.accept(word);
}

void LefParser::expect(std::string_view word) {
  if (lex_.atEnd()) failEof();
  lex_.expect(word);
}

void LefParser::endStatement() {
  if (lex_.atEnd()) failEof();
  const Token& t = lex_.peek();
  if (t.quoted || t.text != ";") failAt(t, "expected ';', found " + quoteToken(t.text));
  lex_.next();
}

Token LefParser::name(std::string_view what) {
  const Token t = next();
  if (t.quoted) failAt(t, "expected " + std::string(what) + ", found the string \"" + std::string(t.text) + "\"");
  if (t.text == ";") failAt(t, "expected " + std::string(what) + ", found ';'");
  if (isNumberText(t.text)) failAt(t, "expected " + std::string(what) + ", found the number " + quoteToken(t.text));
  return t;
}

Token LefParser::keyword(std::string_view where) {
  const Token t = next();
  const unsigned char c = t.text.empty() ? 0 : static_cast<unsigned char>(t.text.front());
  if (t.quoted || !(std::isalpha(c) || c == '_')) {
    failAt(t, "expected a statement in " + std::string(where) + ", found " +
                  (t.quoted ? "a quoted string" : quoteToken(t.text)));
  }
  lex_.upcase(t);  // keywords are case-insensitive: "Via", "layer"
  return t;
}

void LefParser::warn(int line, const std::string& message) {
  tech_.warnings.push_back(lex_.path() + ":" + std::to_string(line) + ": " + message);
  ++tech_.warningCount;
}

void LefParser::defaultUnits(const Token& t) {
  if (tech_.dbuPerMicron > 0) return;
  tech_.dbuPerMicron = kDefaultDbuPerMicron;
  defaultUnitsLine_ = t.line;
  warn(t.line, "length before UNITS DATABASE MICRONS: " + std::to_string(kDefaultDbuPerMicron) +
                   " database units per micron assumed, OpenROAD's default");
}

Dbu LefParser::dist() {
  defaultUnits(peek());
  return lex_.microns(tech_.dbuPerMicron);
}

Dbu LefParser::positiveDist(const std::string& what) {
  const Token t = peek();
  const Dbu v = dist();
  if (v <= 0) failAt(t, what + " must be positive, found " + quoteToken(t.text));
  return v;
}

Dbu LefParser::nonNegativeDist(const std::string& what) {
  const Token t = peek();
  const Dbu v = dist();
  if (v < 0) failAt(t, what + " must not be negative, found " + quoteToken(t.text));
  return v;
}

Area LefParser::area() {
  const Token t = peek();
  defaultUnits(t);
  const double d = tech_.dbuPerMicron;
  const double v = lex_.number() * d * d;
  if (!(std::fabs(v) < 9.0e18)) failAt(t, "area out of range: " + quoteToken(t.text));
  return static_cast<Area>(std::llround(v));
}

double LefParser::number() {
  peek();
  return lex_.number();
}

int64_t LefParser::integer() {
  peek();
  return lex_.integer();
}

Point LefParser::point() {
  const bool paren = accept("(");  // some writers put a point in parentheses: "( x y )"
  const Dbu x = dist();
  const Dbu y = dist();
  if (paren) expect(")");
  return {x, y};
}

Rect LefParser::rect() {
  if (accept("MASK")) maskNumber(false);
  const int line = peek().line;
  const Point a = point();
  const Point b = point();
  // Any two opposite corners, as DEF; a rect without area is kept (it touches, as a line) but warned.
  if (a.x == b.x || a.y == b.y) warn(line, "RECT without area");
  return Rect::fromCorners(a, b);
}

void LefParser::maskNumber(bool via) {
  const Token v = peek();
  const int64_t m = integer();
  if (via ? m < 0 || m > 999 : m < 1) {
    lex_.tally().add(via ? "via mask" : "mask", v.line,
                     "MASK " + quoteToken(v.text) + (via ? ": a via's mask is three digits <top><cut><bottom>"
                                                         : ": a mask number is a positive integer") + " (not kept)");
  }
}

std::vector<Point> LefParser::polygon() {
  if (accept("MASK")) maskNumber(false);
  const int line = peek().line;
  std::vector<Point> pts;
  while (!accept(";")) pts.push_back(point());
  if (pts.size() < 3) lex_.fail(line, "POLYGON needs at least 3 points, found " + std::to_string(pts.size()));
  return pts;
}

LayerId LefParser::layerRef() {
  const Token t = name("a layer name");
  const LayerId id = tech_.findLayer(t.text);
  if (!id.valid()) failAt(t, "unknown layer " + quoteToken(t.text));
  return id;
}

std::string LefParser::restOfStatement() {
  std::string out;
  while (true) {
    const Token t = next();
    if (!t.quoted && t.text == ";") return out;
    if (!out.empty()) out += ' ';
    out += t.text;
  }
}

// ------------------------------------------------------ skip and count --

void LefParser::count(std::string_view block, std::string_view keyword) {
  std::string key;
  key.reserve(block.size() + 1 + keyword.size());
  key.append(block).append(".").append(keyword);
  auto it = skippedIndex_.find(key);
  if (it == skippedIndex_.end()) {
    it = skippedIndex_.emplace(key, tech_.skippedStatements.size()).first;
    tech_.skippedStatements.emplace_back(std::move(key), 0);
  }
  ++tech_.skippedStatements[it->second].second;
  ++tech_.warningCount;
}

void LefParser::noteUnjudged(Layer& layer, std::string rule) {
  for (char& c : rule) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  if (std::find(layer.unjudged.begin(), layer.unjudged.end(), rule) == layer.unjudged.end()) {
    layer.unjudged.push_back(std::move(rule));
  }
}

void LefParser::skipStatement(std::string_view block, const Token& keyword) {
  while (true) {
    const Token t = next();
    if (!t.quoted && t.text == ";") break;
  }
  count(block, keyword.text);
}

void LefParser::skipBlock(std::string_view block, const Token& opener, std::string_view endName) {
  Scope scope(*this, opener.text, endName, opener.line);
  while (true) {
    const Token t = next();
    if (t.quoted || !isKeyword(t.text, "END")) continue;
    if (endName.empty()) break;
    if (lex_.atEnd()) failEof();
    if (!lex_.peek().quoted && (lex_.peek().text == endName || isKeyword(lex_.peek().text, endName))) {
      lex_.next();
      break;
    }
  }
  count(block, opener.text);
}

void LefParser::endBlock(std::string_view blockName) {
  const Token t = next();
  if (t.quoted || t.text != blockName) {
    const OpenBlock& b = open_.back();
    failAt(t, "END " + quoteToken(t.text) + " does not close " + std::string(b.kind) + " " + quoteToken(blockName) +
                  " (opened at line " + std::to_string(b.line) + ")");
  }
}

// ------------------------------------------------------------ the file --

void LefParser::parse() {
  while (!lex_.atEnd()) {
    if (!lex_.peek().quoted && lex_.peek().text.starts_with("&")) {  // "&defines &x = ... ;" (LEF 5.8 macros)
      const Token amp = next();
      skipStatement("LEF", amp);
      warn(amp.line, quoteToken(amp.text) + " skipped: its variables are not expanded");
      continue;
    }
    const Token kw = keyword("the LEF file");
    const std::string_view k = kw.text;
    if (k == "LAYER") {
      parseLayer(kw);
    } else if (k == "VIA") {
      parseVia(kw);
    } else if (k == "VIARULE") {
      parseViaRule(kw);
    } else if (k == "MACRO") {
      parseMacro(kw);
    } else if (k == "SITE") {
      parseSite(kw);
    } else if (k == "UNITS") {
      parseUnits(kw);
    } else if (k == "VERSION") {
      tech_.version = restOfStatement();
    } else if (k == "BUSBITCHARS" || k == "DIVIDERCHAR") {
      const Token v = next();
      if (!v.quoted) failAt(v, std::string(k) + " needs a quoted string, found " + quoteToken(v.text));
      (k == "BUSBITCHARS" ? tech_.busBitChars : tech_.dividerChar) = std::string(v.text);
      endStatement();
    } else if (k == "MANUFACTURINGGRID") {
      const Token t = peek();
      tech_.manufacturingGrid = dist();
      if (tech_.manufacturingGrid <= 0) {  // LEF asks for a positive grid; none is the safe reading
        warn(t.line, "MANUFACTURINGGRID " + std::string(t.text) + " is not a positive length in DBU: ignored");
        tech_.manufacturingGrid = 0;
      }
      endStatement();
    } else if (k == "CLEARANCEMEASURE") {
      const Token v = name("EUCLIDEAN or MAXXY");
      if (!isKeyword(v.text, "EUCLIDEAN") && !isKeyword(v.text, "MAXXY")) {
        failAt(v, "CLEARANCEMEASURE must be EUCLIDEAN or MAXXY, found " + quoteToken(v.text));
      }
      tech_.clearanceMeasure = std::string(v.text);
      endStatement();
    } else if (k == "PROPERTYDEFINITIONS") {
      parsePropertyDefinitions(kw);
    } else if (k == "NONDEFAULTRULE") {
      parseNonDefaultRule(kw);
    } else if (k == "ARRAY") {
      const Token n = name("an array name");
      skipBlock("LEF", kw, n.text);
    } else if (k == "NOISETABLE" || k == "CORRECTIONTABLE" || k == "IRDROP") {
      skipBlock("LEF", kw, k);  // electrical tables: "... END NOISETABLE"
    } else if (k == "SPACING") {  // LEF 5.x "SPACING SAMENET ... END SPACING"
      skipBlock("LEF", kw, "SPACING");
    } else if (k == "BEGINEXT") {
      Scope scope(*this, "BEGINEXT", "", kw.line);
      while (true) {
        const Token t = next();
        if (!t.quoted && isKeyword(t.text, "ENDEXT")) break;
      }
      count("LEF", k);
    } else if (k == "END") {
      const Token t = next();
      if (t.quoted || !isKeyword(t.text, "LIBRARY")) failAt(t, "expected END LIBRARY, found END " + quoteToken(t.text));
      if (!lex_.atEnd()) count("LEF", "text after END LIBRARY");
      break;
    } else {
      skipStatement("LEF", kw);
    }
  }
  for (const WarningTally::Entry& e : lex_.tally().entries()) warn(e.line, WarningTally::text(e));
}

void LefParser::parseUnits(const Token& opener) {
  Scope scope(*this, "UNITS", "", opener.line);
  while (true) {
    const Token kw = keyword("UNITS");
    if (isKeyword(kw.text, "END")) {
      endBlock("UNITS");
      return;
    }
    if (!isKeyword(kw.text, "DATABASE")) {
      skipStatement("UNITS", kw);
      continue;
    }
    expect("MICRONS");
    const Token v = peek();
    const double d = number();
    if (!(d >= 1 && d <= 1.0e6 && d == std::floor(d))) {
      failAt(v, "UNITS DATABASE MICRONS must be a positive integer, found " + quoteToken(v.text));
    }
    const int dbu = static_cast<int>(d);
    if (defaultUnitsLine_ > 0 && dbu != kDefaultDbuPerMicron) {
      failAt(v, "UNITS DATABASE MICRONS " + std::to_string(dbu) + " after a length at line " +
                    std::to_string(defaultUnitsLine_) + ", read with the default of " +
                    std::to_string(kDefaultDbuPerMicron) + ": put UNITS before the first length");
    }
    if (tech_.dbuPerMicron != 0 && tech_.dbuPerMicron != dbu) {
      // LEF lengths are microns whatever the UNITS: a cell LEF's own precision does not change
      // them. OpenROAD keeps the technology's units and warns.
      warn(v.line, "UNITS DATABASE MICRONS " + std::to_string(dbu) + " differs from " +
                       std::to_string(tech_.dbuPerMicron) + " read before: lengths are converted with " +
                       std::to_string(tech_.dbuPerMicron));
    } else {
      tech_.dbuPerMicron = dbu;
    }
    endStatement();
  }
}

void LefParser::parsePropertyDefinitions(const Token& opener) {
  Scope scope(*this, "PROPERTYDEFINITIONS", "", opener.line);
  while (true) {
    const Token kw = keyword("PROPERTYDEFINITIONS");
    if (isKeyword(kw.text, "END")) {
      endBlock("PROPERTYDEFINITIONS");
      return;
    }
    skipStatement("PROPERTYDEFINITIONS", kw);  // "LAYER LEF58_X STRING ;": declares, stores nothing
  }
}

void LefParser::parseSite(const Token& opener) {
  const Token n = name("a site name");
  const bool again = tech_.siteIndex.count(n.text) > 0;
  Scope scope(*this, "SITE", n.text, opener.line);
  Site site;
  site.name = std::string(n.text);
  while (true) {
    const Token kw = keyword("SITE");
    const std::string_view k = kw.text;
    if (k == "END") {
      endBlock(site.name);
      break;
    } else if (k == "CLASS") {
      site.siteClass = restOfStatement();
    } else if (k == "SYMMETRY") {
      site.symmetry = restOfStatement();
    } else if (k == "SIZE") {
      site.width = positiveDist("SITE SIZE width");
      expect("BY");
      site.height = positiveDist("SITE SIZE height");
      endStatement();
    } else {
      skipStatement("SITE", kw);
    }
  }
  if (again) {  // OpenROAD keeps the first definition
    const Site& first = tech_.sites[*tech_.siteIndex.find(site.name)->second];
    const bool same = first.width == site.width && first.height == site.height && first.siteClass == site.siteClass;
    warn(n.line, "SITE " + quoteToken(n.text) + " defined again" + (same ? ", identically" : ", differently") +
                     ": the first definition is kept");
    return;
  }
  tech_.siteIndex.emplace(site.name, SiteId(static_cast<int32_t>(tech_.sites.size())));
  tech_.sites.push_back(std::move(site));
}

// ------------------------------------------------------- entry points --

void readLef(const std::string& path, Tech& tech) {
  Lexer lex = Lexer::fromFile(path);
  if (lex.atEnd()) lex.fail(1, "empty LEF file (no statement)");
  LefParser(lex, tech).parse();
}

void readLefText(const std::string& name, std::string text, Tech& tech) {
  Lexer lex(name, std::move(text));
  if (lex.atEnd()) lex.fail(1, "empty LEF file (no statement)");
  LefParser(lex, tech).parse();
}

}  // namespace xroute
