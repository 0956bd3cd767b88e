// DEF NONDEFAULTRULES: "- name [+ HARDSPACING] { + LAYER l WIDTH w [DIAGWIDTH d] [SPACING s]
// [WIREEXT e] } [+ VIA v] [+ VIARULE r] [+ MINCUTS cut n] [+ PROPERTY name value] ;". A net's
// "+ NONDEFAULTRULE name" names one of them or a LEF NONDEFAULTRULE; its wires on the rule's
// layers get the rule's width (RouteWire::width), which check and the DEF writer use.
#include <cmath>

#include "io/def_parser.hpp"
#include "io/lef_parser.hpp"  // isNumberText

namespace xroute {

// A rule length in DEF units: an integer, or a number rounded to one (OpenROAD's tests write
// "WIDTH 10.1"), rescaled as coordinates are.
Dbu DefParser::ndrLength() {
  const Token t = lex_.peek();
  if (isNumberText(t.text) && t.text.find_first_of(".eE") == std::string_view::npos) return lex_.dbu();
  const double v = lex_.number() * lex_.scaleMul() / lex_.scaleDiv();
  if (!(v >= 0 && v < 1.0e9)) lex_.failAt(t, "bad NONDEFAULTRULE length " + quoteToken(t.text));
  return static_cast<Dbu>(std::llround(v));
}

void DefParser::readNonDefaultRules() {
  const int declared = readSectionCount();
  readEntries("NONDEFAULTRULES", declared, [&] { readNonDefaultRule(); });
}

void DefParser::readNonDefaultRule() {
  const Token nameTok = entryName("a rule name");
  if (design_.ndrIndex.count(nameTok.text)) lex_.failAt(nameTok, "duplicate NONDEFAULTRULE " + quoteToken(nameTok.text));
  NonDefaultRule rule;
  rule.name = std::string(nameTok.text);
  for (Token kw; nextOption(kw);) {
    if (is(kw, "HARDSPACING")) {
      rule.hardSpacing = true;
    } else if (is(kw, "LAYER")) {
      NdrLayer l;
      l.layer = layerAt(lex_.next());  // OpenROAD's parser test names a masterslice layer here
      lex_.expect("WIDTH");
      const Token wt = lex_.peek();
      l.width = ndrLength();
      if (l.width <= 0) lex_.failAt(wt, "NONDEFAULTRULE WIDTH must be positive, found " + quoteToken(wt.text));
      while (true) {
        if (lex_.accept("DIAGWIDTH")) {
          ndrLength();
          countSkip("NONDEFAULTRULES.DIAGWIDTH");
        } else if (lex_.accept("SPACING")) {
          l.spacing = ndrLength();
        } else if (lex_.accept("WIREEXT")) {
          l.wireExt = ndrLength();
        } else {
          break;
        }
      }
      rule.layers.push_back(l);
    } else if (is(kw, "VIA") || is(kw, "VIARULE")) {
      (is(kw, "VIA") ? rule.vias : rule.viaRules).push_back(plainWord("a via name"));
    } else if (is(kw, ";")) {
      unexpected(kw, "a rule option");
    } else {
      skipToOptionEnd();  // MINCUTS, PROPERTY
      countSkip("NONDEFAULTRULES." + std::string(kw.text));
    }
  }
  design_.ndrIndex.emplace(rule.name, static_cast<int>(design_.ndrs.size()));
  design_.ndrs.push_back(std::move(rule));
}

int DefParser::netRule(const Token& nameTok) {
  if (nameTok.quoted || is(nameTok, ";") || is(nameTok, "+")) unexpected(nameTok, "a rule name");
  auto it = design_.ndrIndex.find(nameTok.text);
  if (it != design_.ndrIndex.end()) return it->second;
  auto lef = tech_.ndrIndex.find(nameTok.text);
  if (lef == tech_.ndrIndex.end()) {
    lex_.failAt(nameTok, "unknown NONDEFAULTRULE " + quoteToken(nameTok.text) +
                             " (neither in the DEF's NONDEFAULTRULES nor in the LEF)");
  }
  const int id = static_cast<int>(design_.ndrs.size());
  design_.ndrs.push_back(tech_.ndrs[lef->second]);
  design_.ndrIndex.emplace(design_.ndrs.back().name, id);
  return id;
}

}  // namespace xroute
