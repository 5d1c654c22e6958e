#include "grid/rt_grid_mem.h"

#include <array>

#include <fmt/format.h>

namespace lancer::sc {

rt_grid_mem::rt_grid_mem(sc_core::sc_module_name name)
    : sc_core::sc_module(name),
      clk_i("clk_i"),
      cell_req_valid_o("cell_req_valid_o"),
      cell_req_ready_i("cell_req_ready_i"),
      cell_req_addr_o("cell_req_addr_o"),
      cell_req_tag_o("cell_req_tag_o"),
      cell_rsp_valid_i("cell_rsp_valid_i"),
      cell_rsp_data_i("cell_rsp_data_i"),
      cell_rsp_tag_i("cell_rsp_tag_i"),
      idx_req_valid_o("idx_req_valid_o"),
      idx_req_ready_i("idx_req_ready_i"),
      idx_req_addr_o("idx_req_addr_o"),
      idx_req_tag_o("idx_req_tag_o"),
      idx_rsp_valid_i("idx_rsp_valid_i"),
      idx_rsp_data_i("idx_rsp_data_i"),
      idx_rsp_tag_i("idx_rsp_tag_i"),
      tri_req_valid_o("tri_req_valid_o"),
      tri_req_ready_i("tri_req_ready_i"),
      tri_req_addr_o("tri_req_addr_o"),
      tri_req_tag_o("tri_req_tag_o"),
      tri_rsp_valid_i("tri_rsp_valid_i"),
      tri_rsp_data_i("tri_rsp_data_i"),
      tri_rsp_tag_i("tri_rsp_tag_i") {
  SC_METHOD(edge);
  sensitive << clk_i.pos();
  dont_initialize();
}

void rt_grid_mem::start(const fx::GridImage& image, int latency, int jitter, uint64_t seed) {
  image_ = &image;
  cell_.restart(latency, jitter, seed * 3 + 1);
  idx_.restart(latency, jitter, seed * 3 + 2);
  tri_.restart(latency, jitter, seed * 3 + 3);
  cycle_ = 0;
}

void rt_grid_mem::edge() {
  cell_req_ready_i.write(true);
  idx_req_ready_i.write(true);
  tri_req_ready_i.write(true);
  if (image_ == nullptr) {
    cell_rsp_valid_i.write(false);
    idx_rsp_valid_i.write(false);
    tri_rsp_valid_i.write(false);
    return;
  }
  // The requests of the cycle that ends at this edge, then the responses of the next.
  const uint64_t c = cycle_++;
  if (cell_req_valid_o.read()) cell_.request(c, uint32_t(cell_req_addr_o.read()), uint32_t(cell_req_tag_o.read()));
  if (idx_req_valid_o.read()) idx_.request(c, uint32_t(idx_req_addr_o.read()), uint32_t(idx_req_tag_o.read()));
  if (tri_req_valid_o.read()) tri_.request(c, uint32_t(tri_req_addr_o.read()), uint32_t(tri_req_tag_o.read()));

  auto check = [this](const char* region, uint32_t addr, size_t size) {
    if (addr >= size) {
      const std::string what = fmt::format("{} read at {} outside the image ({} entries)", region, addr, size);
      SC_REPORT_ERROR(name(), what.c_str());
    }
  };
  uint32_t addr = 0, tag = 0;
  const bool cell = cell_.respond(c + 1, addr, tag);
  cell_rsp_valid_i.write(cell);
  if (cell) {
    check("cell table", addr, image_->cells.size());
    const fx::GridCell& e = image_->cells[addr];
    const fx::u128 values[] = {e.first, e.count};
    std::array<uint32_t, size_t(fx::wireWords(GRID_CELL_W))> wire{};
    fx::packFields(fx::kGridCellFields, values, wire);
    cell_rsp_data_i.write(toPort<GRID_CELL_W>(wire));
    cell_rsp_tag_i.write(slot_t(tag));
  }
  const bool idx = idx_.respond(c + 1, addr, tag);
  idx_rsp_valid_i.write(idx);
  if (idx) {
    check("index list", addr, image_->indices.size());
    idx_rsp_data_i.write(idx_data_t(image_->indices[addr]));
    idx_rsp_tag_i.write(slot_t(tag));
  }
  const bool tri = tri_.respond(c + 1, addr, tag);
  tri_rsp_valid_i.write(tri);
  if (tri) {
    check("triangle table", addr, image_->triangles.size());
    fx::TriWire wire{};
    fx::packWire(image_->triangles[addr], wire);
    tri_rsp_data_i.write(toPort<ISECT_TRI_W>(wire));
    tri_rsp_tag_i.write(slot_t(tag));
  }
}

}  // namespace lancer::sc
