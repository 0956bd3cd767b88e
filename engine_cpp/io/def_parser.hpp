// Internal to the DEF reader: the parser state shared by its files
// (def_reader.cpp: header statements, COMPONENTS, BLOCKAGES; def_pins.cpp:
// PINS; def_vias.cpp: VIAS; def_nets.cpp: NETS, SPECIALNETS and routing paths).
#pragma once

#include <algorithm>
#include <optional>

#include <string>
#include <string_view>

#include "db/design.hpp"
#include "db/tech.hpp"
#include "io/lexer.hpp"

namespace xroute {

// Fills `via.shapes` (and bottom/cut/top) of a DEF via generated from a
// VIARULE: a rows x cols cut array centred on the origin with pitch
// cutSize + cutSpacing, metal = the cut array's box grown by the enclosures;
// + ORIGIN shifts everything, + OFFSET shifts each metal layer further.
// + PATTERN (rows listed from the bottom up) drops cuts. Returns false with
// `error` set if the pattern is malformed.
bool generateViaShapes(DefVia& v, std::string& error);

class DefParser {
 public:
  DefParser(Lexer& lex, const Tech& tech, Design& design) : lex_(lex), tech_(tech), design_(design) {}

  void parse();

 private:
  // def_reader.cpp
  void readUnits();
  void readDieArea();
  void readRow();
  void readTracks();
  void readGCellGrid();
  void readComponents();
  void readComponent();
  void readBlockages();
  void readBlockage();
  void skipSection(std::string_view keyword);

  // def_ndr.cpp
  void readNonDefaultRules();
  void readNonDefaultRule();
  Dbu ndrLength();  // a rule length: an integer, or a number rounded (rescaled like coordinates)
  // "+ NONDEFAULTRULE name" of a net: the rule's index in Design::ndrs (a LEF rule is copied there).
  int netRule(const Token& nameTok);

  // def_pins.cpp
  void readPins();
  void readPin();
  IoPinShape readPinRect();     // after + LAYER
  IoPinShape readPinPolygon();  // after + POLYGON: its bounding box
  void resolveIoPinNets();  // after NETS: each IO pin's net by its + NET name

  // def_vias.cpp
  void readVias();
  void readVia();
  ViaShape readViaShape(const Token& kw);
  void readViaLayers(DefVia& v);
  std::string readViaPattern();   // + PATTERN, quotes dropped  // + LAYERS: bottom, cut, top (the cut in any place)
  void finishVia(DefVia& v, int ruleLine);

  // def_nets.cpp
  void readSpecialNets();
  void readSpecialNet();
  void readNets();
  void readNet();
  // One ROUTED/FIXED/COVER/... wiring statement after its keyword, up to (not
  // including) the next net-level '+' or ';'.
  void readRegularWiring(Net& net);
  void readSpecialWiring(SpecialNet& net);
  void readSpecialViaArray(SpecialNet& net, ViaRef ref, Point at, const std::string& shape);
  // A via name in a routing path (after its point), with an optional
  // orientation (only N is kept; others are counted under <section>.VIA.ORIENT).
  ViaRef readPathVia(const Token& viaTok, bool havePoint, std::string_view section);
  // The layer a path continues on after `ref` from `layer`; throws if the via misses it.
  LayerId layerAfterVia(const Token& viaTok, ViaRef ref, LayerId layer) const;

  // Shared helpers (def_reader.cpp).
  // `t` is the unquoted word `w` (keywords in any case; one not in upper case is noted).
  bool is(const Token& t, std::string_view w) const {
    if (t.quoted || !isKeyword(t.text, w)) return false;
    lex_.noteKeyword(t);
    return true;
  }
  bool peekIs(std::string_view w) { return !lex_.atEnd() && is(lex_.peek(), w); }
  Point readPoint();                      // "( x y )"
  // Fails at `line` unless every corner of `r` (a shape placed from values read) is within kMaxDbu.
  void requireInRange(int line, const Rect& r, std::string_view what) const;
  // The bounding box of a via's shapes placed at `at`, checked as requireInRange does.
  void requireViaInRange(int line, ViaRef ref, Point at) const;
  // The pin and OBS shapes of component `c` (which may stick out of its macro's SIZE) placed by
  // `t`, checked as requireInRange does; the message names the component and the macro.
  void requireMacroShapesInRange(int line, const Component& c, const Transform& t);
  // POLYGON points "( x y ) ..." after `kw`, "*" repeating the previous point's coordinate; >= 3.
  std::vector<Point> readPolygonPoints(const Token& kw);
  // A warning "file:line: message" in Design::warnings (and warningCount).
  void warn(int line, const std::string& message);
  // Odd but readable values, summed per file in the lexer's tally (def_checks.cpp): a MASK number
  // that is not one (`via`: before a via, three digits), a RECT whose first corner is not its lower
  // left, a STYLE that no STYLES entry defined; flushTally() turns the tally into warnings.
  void checkMask(const Token& valueTok, int64_t value, bool via);
  void checkCorners(int line, Point a, Point b, std::string_view what);
  void readStyles();
  void useStyle(const Token& valueTok, int64_t value);
  void flushTally();
  LayerId layerAt(const Token& t) const;  // throws on an unknown layer
  LayerId routingLayerAt(const Token& t) const;
  ViaRef findVia(std::string_view name) const;  // invalid if unknown
  Orient orientAt(const Token& t) const;        // throws on a bad orientation
  PlaceStatus readPlacement(const Token& kw, Point& at, Orient& orient);  // after PLACED/FIXED/COVER
  int readSectionCount();                 // "n ;" after a section keyword
  // Expects "END <section>" next (or a '-' item was expected); checks counts.
  bool atSectionEnd(std::string_view section, int declared, int found);
  // The entries of a section whose "n ;" gave `declared`: for each "- ...",
  // consumes the '-' and calls readOne(); then checks "END <section>" and the count.
  template <class ReadOne>
  void readEntries(std::string_view section, int declared, ReadOne&& readOne) {
    for (int found = 0; !atSectionEnd(section, declared, found); ++found) {
      lex_.expect("-");
      readOne();
    }
  }
  Token entryName(std::string_view what);  // the name after '-': not ';', not quoted
  // A reserve() that a bogus huge declared count cannot turn into a huge allocation.
  static size_t saneReserve(int declared) { return static_cast<size_t>(std::clamp(declared, 0, 1 << 20)); }
  std::string quotedChars(size_t count, const std::string& what);
  // A name or value written back as is: any token but ';' and a "quoted string".
  std::string plainWord(const std::string& what);  // "..." of exactly `count` printable chars
  void skipToOptionEnd();                 // skip tokens up to the next '+' or ';' (not consumed)
  void countSkip(std::string_view key, int n = 1);
  [[noreturn]] void unexpected(const Token& t, const std::string& expected) const;
  // The next "+ KEYWORD" of an entry into `kw` (upper-cased in place); false at the entry's ';'.
  bool nextOption(Token& kw);

  Lexer& lex_;
  const Tech& tech_;
  Design& design_;
  std::vector<std::optional<Rect>> macroShapeBox_;  // DBU, by macro id: its pin and OBS shapes' box, once
  std::vector<int64_t> styles_;  // the STYLES section's style numbers (read before NETS)
};

}  // namespace xroute
