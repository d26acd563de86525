#include "tools/results/input_files.h"

#include <set>
#include <vector>

namespace msb {

nlohmann::json parseJsonStrict(const std::string& text, const std::string& where, const InputLimits& limits) {
  // One set of keys per open object; the depth is checked as each array or object opens, so a
  // deeply nested document is refused before it is built.
  std::vector<std::set<std::string>> keys;
  const nlohmann::json::parser_callback_t check = [&](int depth, nlohmann::json::parse_event_t event,
                                                      nlohmann::json& parsed) {
    using E = nlohmann::json::parse_event_t;
    if ((event == E::object_start || event == E::array_start) && depth >= limits.max_depth)
      throw InputFileError(where + ": JSON nested more than " + std::to_string(limits.max_depth) + " levels deep");
    if (event == E::object_start) keys.emplace_back();
    if (event == E::object_end && !keys.empty()) keys.pop_back();
    if (event == E::key && !keys.empty() && !keys.back().insert(parsed.get<std::string>()).second)
      throw InputFileError(where + ": key '" + parsed.get<std::string>() + "' appears twice in one object");
    return true;
  };
  try {
    return nlohmann::json::parse(text, check);
  } catch (const nlohmann::json::parse_error& e) {
    // The library's message carries its own prefix; keep the position and the reason.
    std::string what = e.what();
    const auto colon = what.find("parse error");
    throw InputFileError(where + ": not valid JSON (" + (colon == std::string::npos ? what : what.substr(colon)) + ")");
  } catch (const nlohmann::json::out_of_range&) {
    throw InputFileError(where + ": a number too large for a double");
  } catch (const nlohmann::json::exception&) {
    throw InputFileError(where + ": not valid JSON");
  }
}

nlohmann::json readJsonFile(const std::filesystem::path& path, const InputLimits& limits) {
  return parseJsonStrict(readInputFile(path, limits), path.string(), limits);
}

}  // namespace msb
