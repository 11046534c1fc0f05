// A scene or glTF file's JSON text parsed with repeated keys refused (loaders.h
// parseJsonDocument): JSON keeps only the last of a repeated key, which would silently drop what
// a user wrote.
#include <algorithm>
#include <set>
#include <string>
#include <vector>

#include "core/error.h"
#include "scene/loaders.h"

namespace penumbra::detail {

namespace {

// SAX events into nlohmann's own DOM builder, with the keys of each open object checked for
// duplicates on the way. Not Json::parse with a callback: nlohmann 3.11.2's callback parser
// scans the parent container for discarded values at every object's end (json_sax.hpp,
// json_sax_dom_callback_parser::end_object), quadratic in an array's length: a glTF file of
// 200,000 nodes took 10 s to parse, 1,000,000 would take minutes.
class DuplicateKeyChecker {
 public:
  DuplicateKeyChecker(Json& result, const std::string& path, const std::string& root)
      : dom_(result, /*allow_exceptions=*/true), path_(path), root_(root) {}

  bool null() {
    value();
    return dom_.null();
  }
  bool boolean(bool v) {
    value();
    return dom_.boolean(v);
  }
  bool number_integer(Json::number_integer_t v) {
    value();
    return dom_.number_integer(v);
  }
  bool number_unsigned(Json::number_unsigned_t v) {
    value();
    return dom_.number_unsigned(v);
  }
  bool number_float(Json::number_float_t v, const Json::string_t& s) {
    value();
    return dom_.number_float(v, s);
  }
  bool string(Json::string_t& v) {
    value();
    return dom_.string(v);
  }
  bool binary(Json::binary_t& v) {
    value();
    return dom_.binary(v);
  }
  bool start_object(std::size_t n) {
    value();
    checkDepth();
    stack_.push_back({false, -1, {}, {}});
    return dom_.start_object(n);
  }
  bool key(Json::string_t& k) {
    Frame& f = stack_.back();
    f.key = k;
    if (!f.keys.insert(k).second) {
      f.key.clear();
      const std::string where = pathOf();
      throw Error(path_, (where.empty() ? root_ : where) + ": duplicate key '" + k +
                             "' (JSON would keep only the last one; give it once)");
    }
    return dom_.key(k);
  }
  bool end_object() {
    stack_.pop_back();
    return dom_.end_object();
  }
  bool start_array(std::size_t n) {
    value();
    checkDepth();
    stack_.push_back({true, -1, {}, {}});
    return dom_.start_array(n);
  }
  bool end_array() {
    stack_.pop_back();
    return dom_.end_array();
  }
  template <class Exception>
  bool parse_error(std::size_t position, const std::string& token, const Exception& e) {
    return dom_.parse_error(position, token, e);
  }

 private:
  // One frame per open object or array: the keys seen so far (objects) or the element index
  // (arrays), so that a duplicate is reported with its path, e.g. objects[1].spin.
  struct Frame {
    bool array = false;
    long index = -1;
    std::set<std::string> keys;
    std::string key;  // the current member's key (objects)
  };
  // Nesting past kMaxJsonDepth is refused here, as the document is read: whatever walks it later
  // (tinygltf's conversion, a message quoting a value) recurses per level.
  void checkDepth() const {
    if (stack_.size() < kMaxJsonDepth) return;
    throw Error(path_, abbreviate(pathOf(), 200) + ": nested deeper than " + std::to_string(kMaxJsonDepth) +
                           " arrays and objects");
  }
  // A value starts: inside an array it is the next element.
  void value() {
    if (!stack_.empty() && stack_.back().array) ++stack_.back().index;
  }
  std::string pathOf() const {
    std::string p;
    for (std::size_t i = 0; i < stack_.size(); ++i) {
      const Frame& f = stack_[i];
      if (f.array)
        p += "[" + std::to_string(f.index) + "]";
      else if (i + 1 < stack_.size() || !f.key.empty())
        p += (p.empty() ? "" : ".") + f.key;
    }
    return p;
  }

  nlohmann::detail::json_sax_dom_parser<Json> dom_;
  std::vector<Frame> stack_;
  const std::string& path_;
  const std::string& root_;
};

}  // namespace

std::string shownJson(const Json& v) { return abbreviate(v.dump()); }

std::size_t jsonNestingDepth(const std::string& text) {
  std::size_t depth = 0, deepest = 0;
  bool inString = false, escaped = false;
  for (const char c : text) {
    if (inString) {
      if (escaped)
        escaped = false;
      else if (c == '\\')
        escaped = true;
      else if (c == '"')
        inString = false;
    } else if (c == '"') {
      inString = true;
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return deepest;
}

Json parseJsonDocument(const std::string& text, const std::string& path, const std::string& root) {
  // JSON is UTF-8 (RFC 8259 section 8.1): a UTF-16 or UTF-32 file (a Windows editor's "Unicode")
  // is named as such, not reported as an invalid literal of a raw byte. A byte-order mark, or a
  // NUL among the first two bytes (every JSON text starts with an ASCII character), tells.
  const auto byte = [&](std::size_t i) { return i < text.size() ? (unsigned char)text[i] : 0x100u; };
  if ((byte(0) == 0xFF && byte(1) == 0xFE) || (byte(0) == 0xFE && byte(1) == 0xFF) || byte(0) == 0 || byte(1) == 0)
    throw Error(path, "is UTF-16 or UTF-32 text (a byte-order mark or NUL bytes), not UTF-8: save it as UTF-8");
  Json result;
  DuplicateKeyChecker checker(result, path, root);
  try {
    Json::sax_parse(text, &checker, nlohmann::detail::input_format_t::json, /*strict=*/true,
                    /*ignore_comments=*/root == "scene");
    return result;
  } catch (const Json::exception& e) {
    // parse_error, and out_of_range 406 for a number beyond double ("1e+315", found by
    // fuzzing: tests/fuzz/regressions/json/), which is not a parse_error.
    std::string what = e.what();
    // nlohmann prefixes "[json.exception.parse_error.101] ": keep the readable part.
    if (const auto p = what.find("] "); p != std::string::npos) what = what.substr(p + 2);
    throw Error(path, "invalid JSON: " + what);
  }
}

}  // namespace penumbra::detail
