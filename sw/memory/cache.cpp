#include "memory/cache.h"

namespace lancer::mem {

CacheTags::CacheTags(uint64_t bytes, int ways, int lineBytes)
    : sets_(int(bytes / uint64_t(lineBytes) / uint64_t(ways))), ways_(ways), ways_v_(size_t(sets_) * size_t(ways)) {}

CacheTags::Way* CacheTags::find(uint64_t line) {
  Way* set = &ways_v_[size_t(line % uint64_t(sets_)) * size_t(ways_)];
  for (int w = 0; w < ways_; ++w) {
    if (set[w].lastUse != 0 && set[w].line == line) return &set[w];
  }
  return nullptr;
}

const CacheTags::Way* CacheTags::find(uint64_t line) const { return const_cast<CacheTags*>(this)->find(line); }

bool CacheTags::lookup(uint64_t line) {
  Way* way = find(line);
  if (way == nullptr) return false;
  way->lastUse = ++clock_;
  return true;
}

bool CacheTags::contains(uint64_t line) const { return find(line) != nullptr; }

std::optional<uint64_t> CacheTags::insert(uint64_t line) {
  Way* set = &ways_v_[size_t(line % uint64_t(sets_)) * size_t(ways_)];
  Way* victim = &set[0];
  for (int w = 1; w < ways_ && victim->lastUse != 0; ++w) {
    if (set[w].lastUse < victim->lastUse) victim = &set[w];
  }
  std::optional<uint64_t> evicted;
  if (victim->lastUse != 0) evicted = victim->line;
  victim->line = line;
  victim->lastUse = ++clock_;
  return evicted;
}

}  // namespace lancer::mem
