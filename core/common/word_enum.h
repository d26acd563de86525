// Mode keys as enums: a key whose value is one of a few words (`timing.compute: charged`) is an
// enum class in its config struct, parsed once from its word and compared as a type everywhere
// else. An enum takes part by a `wordsOf` function found by argument-dependent lookup,
//
//   enum class ComputeMode { kFree, kCharged, kModelled };
//   constexpr auto wordsOf(ComputeMode) {
//     return std::array{std::pair{ComputeMode::kFree, "free"}, ...};
//   }
//
// and its key is then `v.key("compute", s.compute)` in the key table (core/common/config_fields.h):
// the YAML layer reads and writes the word, `msbench keys` lists the words.
#pragma once

#include <string>
#include <type_traits>
#include <vector>

namespace msb {

/// An enum whose values have words (see above).
template <class E>
concept WordEnum = std::is_enum_v<E> && requires(E e) {
  wordsOf(e);
};

/// The word of `value` ("" for a value without one, which a table never holds).
template <WordEnum E>
constexpr const char* wordOf(E value) {
  for (const auto& [e, w] : wordsOf(E{}))
    if (e == value) return w;
  return "";
}

/// Sets `out` to the value whose word is `word`; false (out unchanged) if none is.
template <WordEnum E>
bool parseWord(const std::string& word, E& out) {
  for (const auto& [e, w] : wordsOf(E{}))
    if (word == w) {
      out = e;
      return true;
    }
  return false;
}

/// Every word of E, in its table's order.
template <WordEnum E>
std::vector<std::string> wordsList() {
  std::vector<std::string> out;
  for (const auto& [e, w] : wordsOf(E{})) out.emplace_back(w);
  return out;
}

}  // namespace msb
