#include "tools/sweep/markdown_text.h"

#include <cstdio>

namespace msb {

std::string mdText(const std::string& in) {
  std::string out;
  for (size_t i = 0; i < in.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(in[i]);
    // U+200B..U+200F, U+202A..U+202E, U+2066..U+2069 (E2 80 8B..8F, E2 80 AA..AE, E2 81 A6..A9), U+FEFF.
    if (c == 0xE2 && i + 2 < in.size()) {
      const unsigned char b = static_cast<unsigned char>(in[i + 1]), d = static_cast<unsigned char>(in[i + 2]);
      if ((b == 0x80 && ((d >= 0x8B && d <= 0x8F) || (d >= 0xAA && d <= 0xAE))) ||
          (b == 0x81 && d >= 0xA6 && d <= 0xA9)) {
        i += 2;
        continue;
      }
    }
    if (c == 0xEF && i + 2 < in.size() && static_cast<unsigned char>(in[i + 1]) == 0xBB &&
        static_cast<unsigned char>(in[i + 2]) == 0xBF) {
      i += 2;
      continue;
    }
    if (c < 0x20 || c == 0x7F) continue;
    switch (c) {
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '&':
        out += "&amp;";
        break;
      case '[':
      case ']':
      case '|':
      case '*':
      case '`':
      case '\\':
        out += '\\';
        out += char(c);
        break;
      default:
        out += char(c);
    }
  }
  return out;
}

std::string csvField(const std::string& in) {
  if (in.find_first_of(",\"\r\n") == std::string::npos && (in.empty() || in.front() != ' ')) return in;
  std::string out = "\"";
  for (const char c : in) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string terminalText(const std::string& in) {
  std::string out;
  for (const char ch : in) {
    const unsigned char c = static_cast<unsigned char>(ch);
    if (c >= 0x20 && c != 0x7F) {
      out += ch;
      continue;
    }
    char esc[8];
    std::snprintf(esc, sizeof(esc), "\\x%02x", c);
    out += esc;
  }
  return out;
}

}  // namespace msb
