// Scene overrides ("key=value", the CLI's --set) applied to a scene document before it is
// interpreted (loaders.h applyOverrides).
#include <string>
#include <vector>

#include "core/error.h"
#include "scene/loaders.h"

namespace penumbra::detail {

void applyOverrides(Json& doc, const std::vector<std::string>& overrides) {
  for (const std::string& pair : overrides) {
    const std::size_t eq = pair.find('=');
    if (eq == std::string::npos || eq == 0) {
      throw Error("override", "'" + abbreviate(pair) + "': expected key=value");
    }
    const std::string key = pair.substr(0, eq);
    const std::string text = pair.substr(eq + 1);
    // Mitsuba -D style: JSON when it parses ("2", "[1,2]", "true", "\"s\""), a string otherwise;
    // nesting bounded as in files (a 130 KB "[[[...]]]" crashed the messages quoting it).
    if (jsonNestingDepth(text) > kMaxJsonDepth)
      throw Error("override", "'" + abbreviate(key) + "': the value is nested deeper than " +
                                  std::to_string(kMaxJsonDepth) + " arrays and objects");
    Json value = Json::parse(text, nullptr, /*allow_exceptions=*/false);
    if (value.is_discarded()) value = text;

    Json* node = &doc;
    std::string walked;
    std::size_t start = 0;
    while (true) {
      const std::size_t dot = key.find('.', start);
      const std::string part = key.substr(start, dot == std::string::npos ? dot : dot - start);
      if (part.empty()) throw Error("override", "'" + key + "': empty path component");
      if (node->is_null()) *node = Json::object();
      if (node->is_array()) {
        const bool numeric = part.find_first_not_of("0123456789") == std::string::npos;
        if (!numeric || part.size() > 9) {
          throw Error("override", "'" + key + "': '" + walked + "' is an array, '" + part + "' is not an index");
        }
        const std::size_t i = std::stoul(part);
        if (i >= node->size()) {
          throw Error("override", "'" + key + "': index " + part + " out of range ('" + walked + "' has " +
                                      std::to_string(node->size()) + " elements)");
        }
        node = &(*node)[i];
      } else if (node->is_object()) {
        node = &(*node)[part];
      } else {
        throw Error("override", "'" + key + "': '" + walked + "' is " + node->type_name() + ", not an object or array");
      }
      walked += (walked.empty() ? "" : ".") + part;
      if (dot == std::string::npos) break;
      start = dot + 1;
    }
    *node = std::move(value);
  }
}

}  // namespace penumbra::detail
