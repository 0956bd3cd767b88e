// DEF reader: values that are read but not as the DEF language defines them. What xroute does not
// keep (MASK, STYLE) or reads the same either way (a RECT's corners) is a warning, summed per file
// in the lexer's tally and written by flushTally() once the file is read: "file:line: message (the
// first of N in the file)".
#include <algorithm>
#include <string>

#include "io/def_parser.hpp"

namespace xroute {

void DefParser::checkMask(const Token& valueTok, int64_t value, bool via) {
  // A wire's or shape's mask is a positive integer; a via's, three digits <top><cut><bottom>,
  // 0 for "no mask" on that layer (leading zeros may be dropped).
  if (via && (value < 0 || value > 999)) {
    lex_.tally().add("via mask", valueTok.line,
                     "MASK " + quoteToken(valueTok.text) + " before a via: a via's mask is three digits "
                     "<top><cut><bottom> (not kept)");
  } else if (!via && value < 1) {
    lex_.tally().add("mask", valueTok.line,
                     "MASK " + quoteToken(valueTok.text) + ": a mask number is a positive integer (not kept)");
  }
}

void DefParser::checkCorners(int line, Point a, Point b, std::string_view what) {
  // DEF writes a rectangle lower left first; another pair of opposite corners is read the same
  // (as LEF allows any pair), with a warning: an inverted DIEAREA or guide is an error.
  if (a.x <= b.x && a.y <= b.y) return;
  lex_.tally().add("rect corners", line,
                   std::string(what) + " with corners " + std::to_string(a.x) + " " + std::to_string(a.y) + " and " +
                       std::to_string(b.x) + " " + std::to_string(b.y) +
                       ": the first is not the lower left one (read as the rectangle between them)");
}

// STYLES n ; - STYLE num pt pt ... ; ... END STYLES: the numbers are kept (NETS and SPECIALNETS
// refer to them), the shapes skipped.
void DefParser::readStyles() {
  const int declared = readSectionCount();
  readEntries("STYLES", declared, [&] {
    lex_.expect("STYLE");
    styles_.push_back(lex_.integer());
    lex_.skipStatement();
  });
  countSkip("STYLES");
}

void DefParser::useStyle(const Token& valueTok, int64_t value) {
  if (std::find(styles_.begin(), styles_.end(), value) != styles_.end()) return;
  lex_.tally().add("style", valueTok.line,
                   "STYLE " + quoteToken(valueTok.text) + " is not defined in a STYLES section before it (not kept)");
}

void DefParser::flushTally() {
  for (const WarningTally::Entry& e : lex_.tally().entries()) warn(e.line, WarningTally::text(e));
}

}  // namespace xroute
