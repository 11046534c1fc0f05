#include "gl/program_cache.h"

namespace penumbra::gl {

const Program& ProgramCache::get(const std::vector<std::string>& files, const std::vector<std::string>& defines) {
  auto key = std::make_pair(files, defines);
  auto it = programs_.find(key);
  if (it == programs_.end()) it = programs_.emplace(std::move(key), Program(files, defines)).first;
  return it->second;
}

}  // namespace penumbra::gl
