#include "session/fields_loading.h"

#include "session/collective.h"
#include "session/volume_loading.h"

namespace sortlast {

void validateFields(std::vector<FieldSpec>& fields) {
  for (FieldSpec& f : fields) {
    try {
      validateVolume(f.volume);
    } catch (const InputError& e) {
      throw InputError(fieldMessage(e.what(), f.name));
    }
  }
}

std::vector<FieldStep> loadFields(const std::vector<FieldSpec>& fields, const SessionLayout& layout,
                                  MPI_Comm comm) {
  std::vector<FieldStep> out(fields.size());
  for (size_t f = 0; f < fields.size(); ++f) {
    const FieldSpec& spec = fields[f];
    FieldStep& d = out[f];
    d.grid = spec.volume.grid;
    collectively(comm, [&] {
      for (int id : layout.mine) {
        bool present = false;
        const IndexBox box = fieldBoxOf(spec.volume.grid, layout.volume_bricks[size_t(id)].world, present);
        d.boxes.push_back(box);
        d.present.push_back(present ? 1 : 0);
        try {
          d.samples.push_back(present ? readSamples(spec.volume, box) : std::vector<float>());
        } catch (const InputError& e) {
          throw InputError(fieldMessage(e.what(), spec.name));
        }
      }
    });
    // Every rank reaches the Allreduce, then throws or not (a field missing everywhere).
    collectively(comm, [&] {
      std::tie(d.data_min, d.data_max) = globalRange(d.samples, spec.volume.file, comm);
    });
  }
  return out;
}

std::vector<TransferFunction> fieldTransfers(const std::vector<FieldSpec>& fields,
                                             const std::vector<FieldStep>& data) {
  std::vector<TransferFunction> out;
  for (size_t f = 0; f < fields.size(); ++f)
    out.push_back(fields[f].transfer.build(data[f].data_min, data[f].data_max,
                                           data[f].grid.minSpacing()));
  return out;
}

std::vector<int> fieldTableSizes(const std::vector<FieldSpec>& fields) {
  std::vector<int> out;
  for (const FieldSpec& f : fields) out.push_back(f.transfer.table_size);
  return out;
}

std::vector<FieldBrickPart> fieldParts(const std::vector<FieldSpec>& fields,
                                       const std::vector<FieldStep>& data, size_t i) {
  std::vector<FieldBrickPart> parts;
  for (size_t f = 0; f < fields.size(); ++f)
    if (data[f].present[i])
      parts.push_back({int(f), data[f].grid, data[f].boxes[i], &data[f].samples[i]});
  return parts;
}

}  // namespace sortlast
