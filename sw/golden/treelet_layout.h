#pragma once

// What the treelet layouts of the BVH and the octree share (docs/scheduling.md,
// "The treelet layout"): the greedy cut of a tree into treelets (Aila & Karras
// 2010) and their packing into aligned blocks. The units of a tree are named
// by ids (the BVH's interior nodes, the octree's child groups).

#include <algorithm>
#include <cstdint>
#include <functional>
#include <queue>
#include <utility>
#include <vector>

namespace lancer::fx {

// From a treelet's root, the frontier unit of the largest priority (ties: the
// lowest id) joins until the treelet holds `capacity` units; the frontier left
// over roots new treelets, the lowest id first. `children(id, emit)` calls
// emit(priority, child id) for each child unit of `id`. Each treelet's ids
// ascending; the treelets in the order of their roots.
template <class Children>
std::vector<std::vector<uint32_t>> formGreedyTreelets(uint32_t root, size_t capacity, Children children) {
  std::vector<std::vector<uint32_t>> treelets;
  std::priority_queue<uint32_t, std::vector<uint32_t>, std::greater<>> roots;
  roots.push(root);
  using Frontier = std::pair<double, uint32_t>;  // (priority, ~id): the largest, then the lowest id
  while (!roots.empty()) {
    const uint32_t first = roots.top();
    roots.pop();
    std::vector<uint32_t> members{first};
    std::priority_queue<Frontier> frontier;
    const auto open = [&](uint32_t id) {
      children(id, [&](double priority, uint32_t child) { frontier.emplace(priority, ~child); });
    };
    open(first);
    while (members.size() < capacity && !frontier.empty()) {
      const uint32_t next = ~frontier.top().second;
      frontier.pop();
      members.push_back(next);
      open(next);
    }
    for (; !frontier.empty(); frontier.pop()) roots.push(~frontier.top().second);
    std::sort(members.begin(), members.end());
    treelets.push_back(std::move(members));
  }
  return treelets;
}

// The treelets packed next-fit into blocks of `capacity` slots (a block may
// hold several; a treelet never straddles two), block 0 starting after
// `reserved` slots: place(id, slot) for every member. Returns the slots used,
// up to the last member's.
template <class Place>
uint64_t packTreeletsNextFit(const std::vector<std::vector<uint32_t>>& treelets, uint64_t capacity,
                             uint64_t reserved, Place place) {
  uint64_t block = 0, used = reserved;
  for (const std::vector<uint32_t>& t : treelets) {
    if (used + t.size() > capacity) {
      ++block;
      used = 0;
    }
    for (size_t k = 0; k < t.size(); ++k) place(t[k], block * capacity + used + k);
    used += t.size();
  }
  return block * capacity + used;
}

}  // namespace lancer::fx
