#pragma once
// The transfer function as the GL volume renderers use it: a linearly filtered 1D RGBA32F table of
// (r, g, b, tau), the uniforms that map data values onto it, and the empty-space test of a value
// range. The test reads the current function, so skipping follows every change of it.
#include "common/transfer_function.h"
#include "worker/gl_api.h"

namespace sortlast {

class TransferTable {
 public:
  explicit TransferTable(const GlApi& gl);
  ~TransferTable();
  TransferTable(const TransferTable&) = delete;
  TransferTable& operator=(const TransferTable&) = delete;

  // Bakes and uploads the table (left bound to texture unit 1).
  void set(const TransferFunction& tf, int table_size);
  // Whether any value in [vmin, vmax] can have non-zero opacity through the filtered table.
  bool visible(float vmin, float vmax) const;
  // Binds the table to texture unit 1 and sets `program`'s u_table, u_value_map and u_table_map.
  void use(unsigned program) const;
  const TransferFunction& function() const { return tf_; }

 private:
  const GlApi& gl_;
  unsigned texture_ = 0;
  TransferFunction tf_;
  int size_ = 0;
};

}  // namespace sortlast
