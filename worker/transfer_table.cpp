#include "worker/transfer_table.h"

#include <vector>

namespace sortlast {

TransferTable::TransferTable(const GlApi& gl) : gl_(gl) { gl_.GenTextures(1, &texture_); }

TransferTable::~TransferTable() { gl_.DeleteTextures(1, &texture_); }

namespace {
bool same(const TransferFunction& a, const TransferFunction& b) {
  if (a.rangeLo() != b.rangeLo() || a.rangeHi() != b.rangeHi() || a.unitLength() != b.unitLength() ||
      a.points().size() != b.points().size())
    return false;
  for (size_t i = 0; i < a.points().size(); ++i) {
    const TfPoint &p = a.points()[i], &q = b.points()[i];
    if (p.value != q.value || p.r != q.r || p.g != q.g || p.b != q.b || p.a != q.a) return false;
  }
  return true;
}
}  // namespace

void TransferTable::set(const TransferFunction& tf, int table_size) {
  if (version_ > 0 && table_size == size_ && same(tf, tf_)) return;
  tf_ = tf;
  size_ = table_size;
  ++version_;
  table_ = tf.bakeTable(table_size);
  const std::vector<float>& table = table_;
  gl_.ActiveTexture(GL_TEXTURE1);
  gl_.BindTexture(GL_TEXTURE_1D, texture_);
  gl_.TexImage1D(GL_TEXTURE_1D, 0, GL_RGBA32F, table_size, 0, GL_RGBA, GL_FLOAT, table.data());
  gl_.TexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  gl_.TexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  gl_.TexParameteri(GL_TEXTURE_1D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  gl_.check("transfer function upload");
}

bool TransferTable::visible(float vmin, float vmax) const {
  // The table is linearly filtered, so a value can pick up its neighbour entry: widen by one entry.
  double pad = (tf_.rangeHi() - tf_.rangeLo()) / (size_ - 1);
  return tf_.maxOpacity(vmin - pad, vmax + pad) > 0.0;
}

void TransferTable::use(unsigned program) const {
  gl_.Uniform1i(gl_.GetUniformLocation(program, "u_table"), 1);
  double range = tf_.rangeHi() - tf_.rangeLo();
  gl_.Uniform2f(gl_.GetUniformLocation(program, "u_value_map"), float(1.0 / range),
                float(-tf_.rangeLo() / range));
  double n = size_;
  gl_.Uniform2f(gl_.GetUniformLocation(program, "u_table_map"), float((n - 1) / n), float(0.5 / n));
  gl_.ActiveTexture(GL_TEXTURE1);
  gl_.BindTexture(GL_TEXTURE_1D, texture_);
}

}  // namespace sortlast
