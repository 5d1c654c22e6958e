#pragma once

// The registers every traversal unit's cycle model has in the same shape, as
// the RTL shares them (rtl/lib/: rt_fifo, the setup pipeline's
// valid/slot/ray stages, the memory request and visit FIFO entries), for
// rt_grid_model and rt_octree_model. The arithmetic around them is each unit's.

#include <array>
#include <cstddef>
#include <cstdint>

#include "common/rt_trav_unit.h"
#include "golden/isect.h"
#include "isect/rt_isect_types.h"

namespace lancer::sc {

// rt_fifo: Depth entries; in_ready = !full, out_valid = !empty, from the
// occupancy at the start of the cycle.
template <class T, size_t Depth>
struct rt_fifo_model {
  std::array<T, Depth> items{};
  size_t head = 0, size = 0;
  bool full() const { return size == Depth; }
  bool empty() const { return size == 0; }
  const T& front() const { return items[head]; }
  void pop() {
    head = head + 1 == Depth ? 0 : head + 1;
    --size;
  }
  void push(const T& v) {
    size_t tail = head + size;
    if (tail >= Depth) tail -= Depth;
    items[tail] = v;
    ++size;
  }
  void clear() { head = size = 0; }
};

// A memory request FIFO entry (node/cell, index, triangle ports; the index
// buffer's {triangle id, slot}).
struct rt_mem_req {
  uint32_t addr = 0, slot = 0;
};

// A visit FIFO entry: {ray_id, element id} (a cell id, a node id).
struct rt_visit_entry {
  uint32_t rayId = 0, id = 0;
};

// The setup pipeline's valid/slot/ray registers, two stages (the arithmetic
// happens at the slot load, after the second). Per cycle: shift(), then
// load() the ray accepted in it.
struct rt_setup_pipe {
  struct stage {
    bool valid = false;
    int slot = 0;
    isect_ray_t ray{};
  };
  stage s1, s2;

  void clear() { s1.valid = s2.valid = false; }
  void shift() {
    if (s1.valid) {
      s2.slot = s1.slot;
      s2.ray = s1.ray;
    }
    s2.valid = s1.valid;
    s1.valid = false;
  }
  void load(int slot, const isect_ray_t& ray) {
    s1.valid = true;
    s1.slot = slot;
    s1.ray = ray;
  }
};

// The shell's queues, every unit's (rtl/lib/'s traversal shell): the setup
// pipeline, the node/cell, index and triangle request FIFOs, the index buffer
// with its credits, the visit and result FIFOs (Res: the unit's result record).
template <class Res>
struct rt_trav_fifos {
  rt_setup_pipe setup;
  rt_fifo_model<rt_mem_req, MEMREQ_FIFO_DEPTH> nodeQ, idxQ, triQ;
  rt_fifo_model<rt_mem_req, IDX_BUF_DEPTH> idxBuf;  // {triangle id, slot}
  rt_fifo_model<rt_visit_entry, VISIT_FIFO_DEPTH> visitQ;
  rt_fifo_model<Res, RES_FIFO_DEPTH> resQ;
  int credits = IDX_BUF_DEPTH;  // index buffer entries not yet claimed by a request

  void clear() {
    setup.clear();
    nodeQ.clear();
    idxQ.clear();
    triQ.clear();
    idxBuf.clear();
    visitQ.clear();
    resQ.clear();
    credits = IDX_BUF_DEPTH;
  }
};

// A slot's closest-hit record, as rt_trav_shell keeps it: the closest hit so
// far, and before the first one the segment end as a pseudo hit (the bound the
// exit test compares with; fx::walkBound). A bounded ray is exit-tested before
// its first hit; an any-hit ray with a hit is settled (the walk ends without
// the exit test's arithmetic).
struct rt_closest_record {
  bool hasHit = false;
  bool bounded = false;
  bool anyHit = false;
  fx::IsectResult best;

  void start(const fx::QRay& ray) {
    hasHit = false;
    bounded = ray.bounded();
    anyHit = ray.anyHit;
    best = fx::segmentEndBound(ray);
  }
  // rt_closest_hit: does the result replace the record?
  bool takes(const fx::IsectResult& res) const { return res.hit && (!hasHit || fx::closerResult(res, best)); }
  void take(const fx::IsectResult& res) {
    hasHit = true;
    best = res;
  }
  bool wantsCheck() const { return hasHit || bounded; }
  bool settled() const { return anyHit && hasHit; }
  // The unit's result record: {ray id, elements visited, tests, hit, the hit's fields (zero without one)}.
  std::array<fx::u128, 9> resultValues(uint32_t rayId, uint32_t visited, uint64_t tests) const {
    const fx::IsectResult hit = hasHit ? best : fx::IsectResult{};
    return {rayId, visited, tests, hasHit ? 1u : 0u, hit.primId, hit.tNum, hit.det, hit.uNum, hit.vNum};
  }
};

}  // namespace lancer::sc
