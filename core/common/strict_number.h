// The one strict reader of numbers from text, used by the YAML layer, --set values, command-line
// flags and log headers: the whole text must be the number (no trailing characters, no empty
// text), real numbers must be finite and within ±1e12 (no NaN, inf or 1e308), integers must fit
// their type (no silent clamping).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace msb {

/// Largest magnitude accepted for a real number read from text.
inline constexpr double kMaxTextNumber = 1e12;

/// Parses a real number; on failure returns false and sets `why` ("not a number", ...).
bool parseNumber(std::string_view text, double* out, std::string* why);
/// Parses a signed 64-bit integer; on failure returns false and sets `why`.
bool parseInteger(std::string_view text, int64_t* out, std::string* why);
/// Parses an unsigned 64-bit integer (no sign); on failure returns false and sets `why`.
bool parseUnsigned(std::string_view text, uint64_t* out, std::string* why);

}  // namespace msb
