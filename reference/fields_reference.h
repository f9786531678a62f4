#pragma once
// The reference of several fields in one frame (the `volumes` key, scene/fields_scene.h): the
// emission-absorption integral of their mixture, in double, as renderReference (reference/
// reference.h) integrates one field. At a point, field f (where its box holds the point) has value
// v_f, extinction tau_f = tf_f.extinction(v_f) and colour c_f = tf_f.colour(v_f); the mixture of
// media has extinction tau = sum tau_f and emits colour sum tau_f c_f / tau (each medium emits in
// proportion to what it absorbs), so a step of length h has alpha = 1 - exp(-tau h) and colour the
// weighted mean. With one field the step is the one-field arithmetic (tau_1 c_1 / tau_1 = c_1, up
// to one rounding). Rays are the camera's (Camera::pixelRay: from the eye, or parallel from the
// eye plane), run over `box` (the session's: every field's box, fieldsGrid) from t >= 0, cut to
// `clip` (clip.planes, clip.box: common/clip.h clipSpan) in steps of `step` world units, each
// composited as the one-field reference's (cut where a field's values cross a kink of its
// function, each field's optical depth by Simpson's rule); a field outside its own box adds
// nothing, a missing sample (NaN) nothing.
#include <vector>

#include "common/camera.h"
#include "common/clip.h"
#include "io/image.h"
#include "reference/reference.h"
#include "transfer/transfer_function.h"

namespace sortlast {

struct FieldInput {
  WholeVolume vol;
  TransferFunction tf;
};

ImageF renderFieldsReference(const std::vector<FieldInput>& fields, const Box3& box, const Camera& cam,
                             double step, int threads, const ClipRegion& clip);

}  // namespace sortlast
