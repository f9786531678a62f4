#pragma once
// The transfer function as the GL volume renderers use it: a linearly filtered 1D RGBA32F table of
// (r, g, b, tau), the uniforms that map data values onto it, and the empty-space test of a value
// range. The test reads the current function, so skipping follows every change of it. Setting the
// same function again (a session sets it every frame) neither re-bakes nor re-uploads it, and
// version() tells users of the function (the ray caster's block classification) when it changed.
#include <vector>

#include "common/transfer_function.h"
#include "worker/gl_api.h"

namespace sortlast {

class TransferTable {
 public:
  explicit TransferTable(const GlApi& gl);
  ~TransferTable();
  TransferTable(const TransferTable&) = delete;
  TransferTable& operator=(const TransferTable&) = delete;

  // Bakes and uploads the table (left bound to texture unit 1), if it differs from the current one.
  void set(const TransferFunction& tf, int table_size);
  // Counts the changes: equal versions, the same table.
  int version() const { return version_; }
  // The baked table (r, g, b, tau per entry) and the data range it spans.
  const std::vector<float>& entries() const { return table_; }
  double rangeLo() const { return tf_.rangeLo(); }
  double rangeHi() const { return tf_.rangeHi(); }
  // Whether any value in [vmin, vmax] can have non-zero opacity through the filtered table.
  bool visible(float vmin, float vmax) const;
  // Binds the table to texture unit 1 and sets `program`'s u_table, u_value_map and u_table_map.
  void use(unsigned program) const;

 private:
  const GlApi& gl_;
  unsigned texture_ = 0;
  TransferFunction tf_;
  int size_ = 0;
  int version_ = 0;
  std::vector<float> table_;
};

}  // namespace sortlast
