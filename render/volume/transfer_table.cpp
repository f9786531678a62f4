#include "render/volume/transfer_table.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace sortlast {

TransferTable::TransferTable(const GlApi& gl) : gl_(gl) {
  gl_.GenTextures(1, &texture_);
  gl_.GenTextures(1, &texture2d_);
}

TransferTable::~TransferTable() {
  gl_.DeleteTextures(1, &texture_);
  gl_.DeleteTextures(1, &texture2d_);
}

void TransferTable::set(const TransferFunction& tf, int table_size, bool preintegrated) {
  // The same table again (a session sets it every frame): nothing to bake, upload or reclassify.
  if (version_ > 0 && table_size == size_ && preintegrated == preintegrated_ &&
      sameTransferFunction(tf, tf_))
    return;
  tf_ = tf;
  size_ = table_size;
  preintegrated_ = preintegrated;  // (visible() pads by the 2D table's entries then: a new version)
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
  // The 2D pre-integrated table (entry (i, j): the segments between values i and j) is read like
  // the 1D one with n = its size.
  int entries = size_;
  if (preintegrated_) entries = std::min(entries, PreintegrationTable::kDefaultSize);
  return tf_.tableSpanVisible(entries, vmin, vmax);
}

void TransferTable::use(const GlProgram& program) const {
  program.set("u_table", 1);
  const std::array<double, 2> m = tf_.scaledValueMap();
  program.set("u_value_map", glm::vec2(float(m[0]), float(m[1])));
  program.set("u_scale", int(tf_.scale().kind));
  program.set("u_linear_width", float(tf_.scale().linear_width));
  double n = size_;
  program.set("u_table_map", glm::vec2(float((n - 1) / n), float(0.5 / n)));
  gl_.ActiveTexture(GL_TEXTURE1);
  gl_.BindTexture(GL_TEXTURE_1D, texture_);
}

void TransferTable::bindTo(int unit) const {
  gl_.ActiveTexture(GLenum(GL_TEXTURE0 + unit));
  gl_.BindTexture(GL_TEXTURE_1D, texture_);
}

void TransferTable::usePreintegrated(const GlProgram& program, double base_length) {
  const int n = PreintegrationTable::kDefaultSize;
  gl_.ActiveTexture(GL_TEXTURE6);
  gl_.BindTexture(GL_TEXTURE_2D, texture2d_);
  if (built_size_ != n || built_length_ != base_length || !sameTransferFunction(built_tf_, tf_)) {
    // tests/unit/preintegration_test.cpp times the build (26-75 ms for 256 entries here). The
    // tables of the last few lengths are kept: render.sample_spacing: auto renders probe frames
    // at three steps before a frame with a new transfer function (session/auto_spacing.h),
    // and the frame's own step need not be built a second time (when auto probed every view,
    // rebuilding four tables a frame made neghip's frames 1.4x slower).
    if (!sameTransferFunction(cached_tf_, tf_)) cached_.clear(), cached_tf_ = tf_;
    auto it = std::find_if(cached_.begin(), cached_.end(),
                           [&](const auto& c) { return c.first == base_length; });
    if (it == cached_.end()) {
      if (cached_.size() >= kCachedTables) cached_.erase(cached_.begin());
      cached_.emplace_back(base_length, PreintegrationTable::build(tf_, n, base_length).texels());
      it = cached_.end() - 1;
    }
    const std::vector<float>& texels = it->second;
    gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, n, n, 0, GL_RGBA, GL_FLOAT, texels.data());
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gl_.check("pre-integrated table upload");
    built_tf_ = tf_;
    built_length_ = base_length;
    built_size_ = n;
  }
  program.set("u_preint", 6);
  const double m = n;
  program.set("u_preint_map", glm::vec2(float((m - 1) / m), float(0.5 / m)));
  program.set("u_preint_length", float(base_length));
}

}  // namespace sortlast
