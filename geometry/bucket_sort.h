// Counting sort by a small integer key, then a sort of each group by the full item: groups are
// vertex fans, so the sorts are short and the whole order is deterministic. geometry/ only.
#pragma once

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

namespace penumbra::geo {

template <typename T, typename KeyOf>
std::vector<T> bucketSort(const std::vector<T>& items, std::size_t keyCount, KeyOf keyOf) {
  std::vector<std::uint32_t> start(keyCount + 1, 0);
  for (const T& item : items) ++start[keyOf(item) + 1];
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
  std::vector<T> sorted(items.size());
  for (const T& item : items) sorted[next[keyOf(item)]++] = item;
  for (std::size_t k = 0; k < keyCount; ++k) std::sort(sorted.begin() + start[k], sorted.begin() + start[k + 1]);
  return sorted;
}

}  // namespace penumbra::geo
