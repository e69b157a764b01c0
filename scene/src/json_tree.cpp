#include <qverify/scene/json_tree.hpp>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <string_view>
#include <sstream>

namespace qverify {

const char* JsonNode::kind_name() const {
  switch (kind) {
    case Kind::null: return "null";
    case Kind::boolean: return "a boolean";
    case Kind::number: return "a number";
    case Kind::string: return "a string";
    case Kind::array: return "an array";
    case Kind::object: return "an object";
  }
  return "?";
}

namespace {

using nlohmann::json;

/// True when t is a JSON number: -?(0|[1-9][0-9]*)(.[0-9]+)?([eE][+-]?[0-9]+)?
bool json_number_grammar(std::string_view t) {
  std::size_t i = 0;
  auto digits = [&] {
    const std::size_t b = i;
    while (i < t.size() && t[i] >= '0' && t[i] <= '9') ++i;
    return i > b;
  };
  if (i < t.size() && t[i] == '-') ++i;
  if (i < t.size() && t[i] == '0') ++i;
  else if (!digits()) return false;
  if (i < t.size() && t[i] == '.') {
    ++i;
    if (!digits()) return false;
  }
  if (i < t.size() && (t[i] == 'e' || t[i] == 'E')) {
    ++i;
    if (i < t.size() && (t[i] == '+' || t[i] == '-')) ++i;
    if (!digits()) return false;
  }
  return i == t.size();
}

/// nlohmann converts every number literal to a double on the way and refuses
/// literals beyond the double range (1e400), although an exact scene may hold
/// them. So each well-formed number literal is taken out first: its text is
/// recorded (document order) and it is overwritten by "0" padded with spaces
/// (byte offsets stay the same). The SAX callbacks take the texts back in order.
std::vector<std::string> take_out_numbers(std::string& text) {
  std::vector<std::string> numbers;
  std::size_t i = 0;
  const std::size_t n = text.size();
  while (i < n) {
    const char c = text[i];
    if (c == '"') {  // skip a string, honouring escapes
      ++i;
      while (i < n && text[i] != '"') i += text[i] == '\\' ? 2 : 1;
      ++i;
    } else if (c == '-' || (c >= '0' && c <= '9')) {
      std::size_t j = i;
      while (j < n && (text[j] == '-' || text[j] == '+' || text[j] == '.' || text[j] == 'e' || text[j] == 'E' ||
                       (text[j] >= '0' && text[j] <= '9')))
        ++j;
      const std::string_view tok(text.data() + i, j - i);
      if (json_number_grammar(tok)) {
        numbers.emplace_back(tok);
        text[i] = '0';
        for (std::size_t k = i + 1; k < j; ++k) text[k] = ' ';
      }
      i = j;
    } else {
      ++i;
    }
  }
  return numbers;
}

/// SAX handler building a JsonNode tree; tracks the JSON path for messages.
class TreeBuilder : public nlohmann::json_sax<json> {
 public:
  TreeBuilder(std::string file, const JsonLimits& limits, std::vector<std::string> numbers)
      : file_(std::move(file)), limits_(limits), numbers_(std::move(numbers)) {}

  JsonNode root;

  bool null() override { return put(JsonNode{}); }
  bool boolean(bool b) override {
    JsonNode n;
    n.kind = JsonNode::Kind::boolean;
    n.boolean = b;
    return put(std::move(n));
  }
  // Every literal was replaced by 0 (see take_out_numbers): take the next recorded text.
  bool number_integer(number_integer_t) override { return number(); }
  bool number_unsigned(number_unsigned_t) override { return number(); }
  bool number_float(number_float_t, const string_t&) override { return number(); }
  bool string(string_t& s) override {
    JsonNode n;
    n.kind = JsonNode::Kind::string;
    n.text = s;
    return put(std::move(n));
  }
  bool binary(binary_t&) override { throw InputError(file_, path(), "binary values are not JSON"); }
  bool start_object(std::size_t) override {
    JsonNode n;
    n.kind = JsonNode::Kind::object;
    return open(std::move(n));
  }
  bool key(string_t& k) override {
    JsonNode* top = stack_.back();
    for (const auto& m : top->members)
      if (m.first == k) throw InputError(file_, path() + (path().empty() ? "" : ".") + k, "duplicate key");
    key_ = k;
    have_key_ = true;
    return true;
  }
  bool end_object() override { return close(); }
  bool start_array(std::size_t) override {
    JsonNode n;
    n.kind = JsonNode::Kind::array;
    return open(std::move(n));
  }
  bool end_array() override { return close(); }
  bool parse_error(std::size_t pos, const std::string&, const nlohmann::detail::exception& ex) override {
    std::string msg = ex.what();
    // nlohmann's messages start with "[json.exception.parse_error.101] "; keep the rest.
    const auto b = msg.find("] ");
    if (b != std::string::npos) msg = msg.substr(b + 2);
    // The "last read: '...'" excerpt shows the text with its number literals masked: drop it
    // (line, column and byte locate the problem).
    const auto lr = msg.find("; last read: '");
    if (lr != std::string::npos) {
      const auto end = msg.find('\'', lr + 14);
      msg.erase(lr, end == std::string::npos ? std::string::npos : end + 1 - lr);
    }
    throw InputError(file_, path(), "invalid JSON at byte " + std::to_string(pos) + ": " + msg);
  }

 private:
  std::string file_;
  JsonLimits limits_;
  std::vector<std::string> numbers_;
  std::size_t next_number_ = 0;
  std::vector<JsonNode*> stack_;
  std::string key_;
  bool have_key_ = false;
  bool have_root_ = false;

  std::string path() const {
    std::string p;
    const JsonNode* parent = nullptr;
    for (const JsonNode* n : stack_) {
      if (parent) {
        if (parent->kind == JsonNode::Kind::array) p += "[" + std::to_string(parent->items.size() - 1) + "]";
        else p += (p.empty() ? "" : ".") + parent->members.back().first;
      }
      parent = n;
    }
    if (parent && parent->kind == JsonNode::Kind::object && have_key_) p += (p.empty() ? "" : ".") + key_;
    if (parent && parent->kind == JsonNode::Kind::array) p += "[" + std::to_string(parent->items.size()) + "]";
    return p;
  }

  bool number() {
    if (next_number_ >= numbers_.size()) throw InputError(file_, path(), "internal: number literals out of step");
    JsonNode n;
    n.kind = JsonNode::Kind::number;
    n.text = std::move(numbers_[next_number_++]);
    return put(std::move(n));
  }

  JsonNode* put_ptr(JsonNode&& n) {
    if (stack_.empty()) {
      root = std::move(n);
      have_root_ = true;
      return &root;
    }
    JsonNode* top = stack_.back();
    if (top->kind == JsonNode::Kind::array) {
      top->items.push_back(std::move(n));
      return &top->items.back();
    }
    top->members.emplace_back(key_, std::move(n));
    have_key_ = false;
    return &top->members.back().second;
  }
  bool put(JsonNode&& n) {
    put_ptr(std::move(n));
    return true;
  }
  bool open(JsonNode&& n) {
    if (stack_.size() >= limits_.max_depth)
      throw InputError(file_, path(), "nesting deeper than " + std::to_string(limits_.max_depth) + " levels");
    JsonNode* p = put_ptr(std::move(n));
    stack_.push_back(p);
    return true;
  }
  bool close() {
    stack_.pop_back();
    have_key_ = false;
    return true;
  }
};

}  // namespace

JsonNode parse_json_tree(const std::string& text, const std::string& file, const JsonLimits& limits) {
  if (text.size() > limits.max_bytes)
    throw InputError(file, "", "file is larger than " + std::to_string(limits.max_bytes) + " bytes");
  // nlohmann's lexer reads a NUL byte as the end of its input, so a document followed by a NUL and
  // anything at all was accepted (audit 37b F5); JSON text has no NUL outside strings, and inside
  // them it must be escaped
  if (const std::size_t nul = text.find('\0'); nul != std::string::npos)
    throw InputError(file, "", "a NUL byte at byte offset " + std::to_string(nul) + " (JSON text has none)");
  std::string masked = text;
  std::vector<std::string> numbers = take_out_numbers(masked);
  TreeBuilder b(file, limits, std::move(numbers));
  json::sax_parse(masked, &b, json::input_format_t::json, true, false);
  return std::move(b.root);
}

std::string read_text_file(const std::string& file, std::size_t max_bytes) {
  std::error_code ec;
  if (std::filesystem::exists(file, ec) && !std::filesystem::is_regular_file(file, ec))
    throw InputError(file, "", "not a regular file");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file, "", "cannot open file");
  in.seekg(0, std::ios::end);
  const auto size = in.tellg();
  if (size < 0) throw InputError(file, "", "cannot read file (not a regular file?)");
  if (static_cast<std::size_t>(size) > max_bytes)
    throw InputError(file, "", "file is larger than " + std::to_string(max_bytes) + " bytes");
  in.seekg(0);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace qverify
