// Text from files (names, ids, paths, messages) made inert for every output the report writes:
// report.md and the page made from it, its CSV files and its lines on the terminal (docs/sweeps.md,
// "Opening a colleague's report").
#pragma once

#include <string>

namespace msb {

/// `in` as Markdown text: HTML's < > & as entities; [ ] | * ` and \ escaped (no link, image,
/// table cell, emphasis or code span of its own); characters that reorder or hide text
/// (bidirectional controls, zero-width marks) and control characters removed. Ordinary names
/// are unchanged.
std::string mdText(const std::string& in);

/// `in` as one CSV field (RFC 4180): quoted, its quotes doubled, when it holds a comma, a quote,
/// a line break or a leading blank; unchanged otherwise (so ordinary names are as before).
std::string csvField(const std::string& in);

/// `in` for a terminal line: control characters (line breaks, escape sequences) written as
/// `\xNN`, so a name can neither start a line of its own nor drive the terminal.
std::string terminalText(const std::string& in);

}  // namespace msb
