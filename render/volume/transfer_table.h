#pragma once
// The transfer function as the GL volume renderers use it: a linearly filtered 1D RGBA32F table of
// (r, g, b, tau), the uniforms that map data values onto it, and the empty-space test of a value
// range. The test reads the current function, so skipping follows every change of it. Setting the
// same function again (a session sets it every frame) neither re-bakes nor re-uploads it, and
// version() tells users of the function (the ray caster's block classification) when it changed.
//
// With pre-integration (transfer.preintegrated) it also holds the 2D table of ray segments
// (transfer/preintegration.h) as a linearly filtered RGBA32F texture, (C_r, C_g, C_b, optical
// depth) at texel centres: built on first use for a base length, and again only when the
// transfer function or that length changes.
#include <vector>

#include "transfer/preintegration.h"
#include "transfer/transfer_function.h"
#include "render/gl/gl_api.h"
#include "render/gl/gl_program.h"

namespace sortlast {

class TransferTable {
 public:
  explicit TransferTable(const GlApi& gl);
  ~TransferTable();
  TransferTable(const TransferTable&) = delete;
  TransferTable& operator=(const TransferTable&) = delete;

  // Bakes and uploads the 1D table (left bound to texture unit 1); with `preintegrated`, the
  // renderers draw segments from the 2D table (usePreintegrated()).
  void set(const TransferFunction& tf, int table_size, bool preintegrated = false);
  bool preintegrated() const { return preintegrated_; }
  // Counts the changes: equal versions, the same table.
  int version() const { return version_; }
  // The baked table (r, g, b, tau per entry) and the data range it spans.
  const std::vector<float>& entries() const { return table_; }
  double rangeLo() const { return tf_.rangeLo(); }
  double rangeHi() const { return tf_.rangeHi(); }
  // Whether any value in [vmin, vmax] can have non-zero opacity through the filtered table (the
  // 2D one too: a segment between two values in the range).
  bool visible(float vmin, float vmax) const;
  // Binds the table to texture unit 1 and sets `program`'s u_table, u_value_map, u_scale,
  // u_linear_width (render/volume/value_scale.glsl) and u_table_map.
  void use(const GlProgram& program) const;
  // Builds the 2D table for segments of `base_length` (world units) if it is stale, binds it to
  // texture unit 6 and sets `program`'s u_preint, u_preint_map and u_preint_length.
  void usePreintegrated(const GlProgram& program, double base_length);
  const TransferFunction& function() const { return tf_; }
  // Entries of the 1D table, and binding it to texture unit `unit` (several fields' tables).
  int size() const { return size_; }
  void bindTo(int unit) const;

 private:
  const GlApi& gl_;
  unsigned texture_ = 0, texture2d_ = 0;
  TransferFunction tf_;
  int size_ = 0;
  bool preintegrated_ = false;
  // What the 2D texture holds: the function and length it was built for (size 0: nothing yet).
  TransferFunction built_tf_;
  // Pre-integrated texels by segment length, for the function cached_tf_ (4 x 1 MiB at most).
  static constexpr size_t kCachedTables = 4;
  TransferFunction cached_tf_;
  std::vector<std::pair<double, std::vector<float>>> cached_;
  double built_length_ = 0.0;
  int built_size_ = 0;
  int version_ = 0;
  std::vector<float> table_;
};

}  // namespace sortlast
