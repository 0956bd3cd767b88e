// LEF NONDEFAULTRULE blocks: per-layer WIDTH / SPACING / WIREEXTENSION kept in Tech::ndrs; the
// rule's VIA definitions are ordinary vias (a DEF may name them); USEVIA / USEVIARULE names are
// kept; everything else (MINCUTS, PROPERTY, RESISTANCE, ...) is skipped and counted.
#include "io/lef_parser.hpp"

namespace xroute {

void LefParser::parseNdrLayer(NonDefaultRule& rule, const Token& opener) {
  const Token n = name("a layer name");
  const LayerId id = tech_.findLayer(n.text);
  if (!id.valid()) failAt(n, "unknown layer " + quoteToken(n.text));
  Scope scope(*this, "LAYER", n.text, opener.line);
  NdrLayer l;
  l.layer = id;
  while (true) {
    const Token kw = keyword("NONDEFAULTRULE LAYER");
    const std::string_view k = kw.text;
    if (k == "END") {
      endBlock(n.text);
      break;
    } else if (k == "WIDTH") {
      l.width = positiveDist("NONDEFAULTRULE WIDTH on " + quoteToken(n.text));
      endStatement();
    } else if (k == "SPACING") {
      l.spacing = nonNegativeDist("NONDEFAULTRULE SPACING on " + quoteToken(n.text));
      endStatement();
    } else if (k == "WIREEXTENSION") {
      l.wireExt = nonNegativeDist("NONDEFAULTRULE WIREEXTENSION on " + quoteToken(n.text));
      endStatement();
    } else {
      skipStatement("NONDEFAULTRULE.LAYER", kw);  // DIAGWIDTH, RESISTANCE, CAPACITANCE, ...
    }
  }
  rule.layers.push_back(l);
}

void LefParser::parseNonDefaultRule(const Token& opener) {
  const Token n = name("a rule name");
  if (tech_.ndrIndex.count(n.text)) failAt(n, "duplicate NONDEFAULTRULE " + quoteToken(n.text));
  Scope scope(*this, "NONDEFAULTRULE", n.text, opener.line);
  NonDefaultRule rule;
  rule.name = std::string(n.text);
  while (true) {
    const Token kw = keyword("NONDEFAULTRULE");
    const std::string_view k = kw.text;
    if (k == "END") {
      // "END name"; some files close the rule with a bare END, which the Si2 parser accepts.
      if (!lex_.atEnd() && !lex_.peek().quoted && lex_.peek().text == rule.name) {
        lex_.next();
      } else {
        warn(kw.line, "NONDEFAULTRULE " + quoteToken(rule.name) + " closed by a bare END");
      }
      break;
    } else if (k == "HARDSPACING") {
      rule.hardSpacing = true;
      endStatement();
    } else if (k == "LAYER") {
      parseNdrLayer(rule, kw);
    } else if (k == "VIA") {
      const std::string viaName(peek().text);
      parseVia(kw);
      rule.vias.push_back(viaName);
    } else if (k == "USEVIA" || k == "USEVIARULE") {
      (k == "USEVIA" ? rule.vias : rule.viaRules).push_back(std::string(name("a via name").text));
      endStatement();
    } else if (k == "SPACING") {  // LEF 5.4 "SPACING SAMENET ... END SPACING"
      skipBlock("NONDEFAULTRULE", kw, "SPACING");
    } else {
      skipStatement("NONDEFAULTRULE", kw);  // MINCUTS, PROPERTY, ...
    }
  }
  tech_.ndrIndex.emplace(rule.name, static_cast<int>(tech_.ndrs.size()));
  tech_.ndrs.push_back(std::move(rule));
}

}  // namespace xroute
