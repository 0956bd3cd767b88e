// LEF58 property strings: a layer PROPERTY whose value is a quoted string in
// its own small syntax. Parsed here with a Lexer over the string; errors are
// reported at the line of the offending word in the LEF file.
//
// LEF58_CORNERSPACING (ispd19 files):
//   CORNERSPACING CONVEXCORNER [EXCEPTEOL eolWidth]
//       WIDTH w1 SPACING s1 [WIDTH w2 SPACING s2 ...] ;
//   CORNERSPACING CONCAVECORNER WIDTH w SPACING s ... ;
// Forms with other keywords (SAMEMASK, CORNERONLY, EXCEPTJOGLENGTH,
// HORIZONTAL/VERTICAL spacings, ...) are not modelled: such a rule is
// dropped whole and counted as "LAYER.LEF58_CORNERSPACING.<WORD>".
#include "io/lef_parser.hpp"

namespace xroute {

namespace {

bool isWord(const Token& t, std::string_view w) { return !t.quoted && t.text == w; }

// Skips the rest of one ';'-ended rule inside the string (or to its end).
void skipRule(Lexer& sub) {
  while (!sub.atEnd()) {
    if (isWord(sub.next(), ";")) return;
  }
}

}  // namespace

void LefParser::parseLef58CornerSpacing(Layer& layer, const Token& valueTok) {
  if (tech_.dbuPerMicron <= 0) failAt(valueTok, "LEF58_CORNERSPACING before UNITS DATABASE MICRONS (units unknown)");
  const int dbu = tech_.dbuPerMicron;
  Lexer sub(lex_.path(), std::string(valueTok.text));
  try {
    while (!sub.atEnd()) {
      const Token head = sub.next();
      if (isWord(head, ";")) continue;
      if (!isWord(head, "CORNERSPACING")) {
        noteUnjudged(layer, "LEF58_CORNERSPACING " + std::string(head.text));
        skipRule(sub);
        count("LAYER.LEF58_CORNERSPACING", head.text);
        continue;
      }
      CornerSpacingRule rule;
      bool supported = true;
      std::string_view unsupportedWord;
      while (!sub.atEnd() && !isWord(sub.peek(), ";")) {
        const Token t = sub.next();
        if (isWord(t, "CONVEXCORNER")) {
          rule.convexCorner = true;
        } else if (isWord(t, "CONCAVECORNER")) {
          rule.concaveCorner = true;
        } else if (isWord(t, "EXCEPTEOL")) {
          rule.exceptEol = true;
          rule.eolWidth = sub.microns(dbu);
        } else if (isWord(t, "WIDTH")) {
          const Token wTok = sub.peek();
          const Dbu w = sub.microns(dbu);
          if (!rule.widths.empty() && w < rule.widths.back()) {
            sub.failAt(wTok, "WIDTH values must be ascending, found " + quoteToken(wTok.text));
          }
          sub.expect("SPACING");
          rule.widths.push_back(w);
          rule.spacings.push_back(sub.microns(dbu));
        } else {
          supported = false;
          unsupportedWord = t.text;
          skipRule(sub);
          break;
        }
      }
      if (supported) {
        sub.accept(";");
        if (rule.concaveCorner) noteUnjudged(layer, "LEF58_CORNERSPACING CONCAVECORNER");
        if (rule.widths.empty()) sub.fail(sub.line(), "CORNERSPACING without WIDTH ... SPACING ...");
        if (rule.convexCorner == rule.concaveCorner) {
          sub.fail(sub.line(), "CORNERSPACING needs exactly one of CONVEXCORNER and CONCAVECORNER");
        }
        layer.cornerSpacings.push_back(std::move(rule));
      } else {
        noteUnjudged(layer, "LEF58_CORNERSPACING " + std::string(unsupportedWord));
        count("LAYER.LEF58_CORNERSPACING", unsupportedWord);
      }
    }
  } catch (const InputError& e) {
    // Lines inside the string count from the line where the string starts.
    const int line = valueTok.line + (e.line() > 0 ? e.line() - 1 : 0);
    throw InputError(lex_.path(), line, "in LEF58_CORNERSPACING: " + e.message());
  }
}

}  // namespace xroute
