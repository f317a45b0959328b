// Scanline table SRAM: one entry (T.u, T.v, S.u, S.v) per constant-depth line.
// Split into an even and an odd bank so that a line and its correction
// neighbour (k and k +- 1) are read in the same cycle from single-port banks
// (two-port with early_walk: docs/area.md).
#pragma once

#include <cstdint>
#include <stdexcept>
#include <vector>

#include "setup_engine.hpp"

namespace cdsim {

class ScanlineTable {
 public:
  explicit ScanlineTable(int depth) : entries_(static_cast<size_t>(depth)) {}

  // Starts a band whose lines begin at first_line.
  void start_band(int64_t first_line) {
    base_ = first_line;
    used_ = 0;
  }
  void write(int64_t line, const TableEntry& entry) {
    entries_.at(address(line)) = entry;
    used_ = std::max<int64_t>(used_, line - base_ + 1);
    high_water_ = std::max(high_water_, used_);
  }
  const TableEntry& read(int64_t line) const { return entries_[address(line)]; }
  // Lines first .. last of the current band, checked once: entry k is at
  // [k - first].
  const TableEntry* read_lines(int64_t first, int64_t last) const {
    address(last);
    return &entries_[address(first)];
  }

  int depth() const { return static_cast<int>(entries_.size()); }
  int64_t high_water() const { return high_water_; }

 private:
  size_t address(int64_t line) const {
    const int64_t a = line - base_;
    if (a < 0 || a >= static_cast<int64_t>(entries_.size()))
      throw std::logic_error("scanline table: line outside the current band");
    return static_cast<size_t>(a);
  }
  std::vector<TableEntry> entries_;
  int64_t base_ = 0;
  int64_t used_ = 0;
  int64_t high_water_ = 0;
};

}  // namespace cdsim
