// Programs by shader files and defines, built on first use and kept: the one cache every
// technique uses for its variants (dcs's counter layouts, the shadow maps' resolves, pcss's
// modes) instead of a map of its own.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "gl/objects.h"

namespace penumbra::gl {

class ProgramCache {
 public:
  // The program of `files` compiled with `defines` (gl::Program); the reference stays valid
  // until clear() or the cache's end.
  const Program& get(const std::vector<std::string>& files, const std::vector<std::string>& defines = {});
  void clear() { programs_.clear(); }
  std::size_t size() const { return programs_.size(); }

 private:
  std::map<std::pair<std::vector<std::string>, std::vector<std::string>>, Program> programs_;
};

}  // namespace penumbra::gl
