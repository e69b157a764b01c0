#pragma once
/// \file json_tree.hpp
/// A JSON tree that keeps every number's literal text (nlohmann's SAX parser
/// hands it over), so exact arithmetic reads `0.1` as 1/10. Rejects duplicate
/// keys and nesting deeper than a limit; members stay in document order.

#include <qverify/scene/input_error.hpp>

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace qverify {

struct JsonNode {
  enum class Kind { null, boolean, number, string, array, object };
  Kind kind = Kind::null;
  bool boolean = false;
  std::string text;  ///< number literal or string value
  std::vector<JsonNode> items;
  std::vector<std::pair<std::string, JsonNode>> members;

  const JsonNode* find(const std::string& key) const {
    for (const auto& m : members)
      if (m.first == key) return &m.second;
    return nullptr;
  }
  const char* kind_name() const;
};

struct JsonLimits {
  std::size_t max_depth = 64;
  std::size_t max_bytes = std::size_t(64) << 20;
};

/// Parses `text`; on failure throws InputError(file, path-so-far, message).
JsonNode parse_json_tree(const std::string& text, const std::string& file, const JsonLimits& limits = {});

/// Reads a whole file, refusing files larger than max_bytes (InputError).
std::string read_text_file(const std::string& file, std::size_t max_bytes);

}  // namespace qverify
