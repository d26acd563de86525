// Text from files (names, ids, paths, messages) made inert for report.md and the page made from
// it (docs/sweeps.md, "Opening a colleague's report").
#pragma once

#include <string>

namespace msb {

/// `in` as Markdown text: HTML's < > & as entities; [ ] | * ` and \ escaped (no link, image,
/// table cell, emphasis or code span of its own); characters that reorder or hide text
/// (bidirectional controls, zero-width marks) and control characters removed. Ordinary names
/// are unchanged.
std::string mdText(const std::string& in);

}  // namespace msb
