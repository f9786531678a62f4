#pragma once
// Several fields (the `volumes` key, scene/fields_scene.h) on one rank: each field's part of each
// of the rank's bricks (render/volume/field_bricks.h: its samples inside the brick's box with one
// ghost sample; none where it does not reach), read per brick from its own file or procedural
// field, and its data range over every rank (its transfer function's `auto` range).
#include <mpi.h>

#include <vector>

#include "render/volume/field_bricks.h"
#include "scene/scene.h"
#include "session/session_layout.h"
#include "session/value_histogram.h"

namespace sortlast {

struct FieldStep {
  std::vector<IndexBox> boxes;                // per brick of layout.mine (on the field's grid)
  std::vector<char> present;                  // per brick: the field reaches it
  std::vector<std::vector<float>> samples;    // per brick (empty where absent)
  double data_min = 0, data_max = 0;          // over every rank
  GridGeometry grid;                          // the field's (a file's own, read from it)
  // Rank 0: every sample of the field counted once (value_histogram.h), in its transfer.scale.
  ValueHistogram histogram;
};

// Checks each field's file (throws InputError naming `volumes[i]`) and fills in the grids files
// give. Every rank does the same.
void validateFields(std::vector<FieldSpec>& fields);

// Every field's parts of this rank's bricks, its range and histogram. Collective; errors end the
// call on every rank.
std::vector<FieldStep> loadFields(const std::vector<FieldSpec>& fields, const SessionLayout& layout,
                                  MPI_Comm comm);

// The transfer functions of a step's fields (as `fields` gives them: a request may change them),
// each over its own data range and voxel spacing.
std::vector<TransferFunction> fieldTransfers(const std::vector<FieldSpec>& fields,
                                             const std::vector<FieldStep>& data);

// Each field's transfer.table_size.
std::vector<int> fieldTableSizes(const std::vector<FieldSpec>& fields);

// The parts of brick i (of layout.mine) the ray caster takes (pointing into `data`).
std::vector<FieldBrickPart> fieldParts(const std::vector<FieldSpec>& fields,
                                       const std::vector<FieldStep>& data, size_t i);

}  // namespace sortlast
