#pragma once

// The tag array of a set-associative, read-only cache with true LRU
// replacement: which lines it holds, nothing about timing (memory/system.h
// adds that). Lines are byte addresses divided by the line size; a line's set
// is its low bits.

#include <cstdint>
#include <optional>
#include <vector>

namespace lancer::mem {

class CacheTags {
 public:
  // `bytes` and `lineBytes` powers of two, ways dividing the line count; the
  // caller validates (MemoryConfig::validate).
  CacheTags(uint64_t bytes, int ways, int lineBytes);

  int sets() const { return sets_; }
  int ways() const { return ways_; }
  // True if the line is present; a hit becomes the set's most recently used.
  bool lookup(uint64_t line);
  // Whether present, without touching the LRU order.
  bool contains(uint64_t line) const;
  // Places a line that is not present as the most recently used; returns the
  // line it evicted, if the set was full.
  std::optional<uint64_t> insert(uint64_t line);

 private:
  struct Way {
    uint64_t line = 0;
    uint64_t lastUse = 0;  // 0: invalid
  };
  Way* find(uint64_t line);
  const Way* find(uint64_t line) const;

  int sets_, ways_;
  std::vector<Way> ways_v_;  // set-major: set s holds ways_v_[s*ways .. s*ways+ways)
  uint64_t clock_ = 0;
};

}  // namespace lancer::mem
