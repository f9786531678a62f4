#include "session/fields_loading.h"

#include "session/collective.h"
#include "session/volume_loading.h"

namespace sortlast {

namespace {

// This rank's share of a field's histogram. A field's parts overlap (each brick holds the samples
// of its box and one beyond), so each sample is counted by the one brick whose cell holds it:
// per axis the half-open slab [plane c, plane c + 1) of the layout's planes, the outer slabs
// reaching to infinity. Adjacent bricks share their plane's value, so the slabs partition space
// and every sample of the field is counted once over all ranks.
std::vector<long long> countOwnSamples(const FieldStep& d, const SessionLayout& layout, const HistogramBinner& binner) {
  std::vector<long long> bins(kHistogramBins, 0);
  for (size_t i = 0; i < layout.mine.size(); ++i) {
    if (!d.present[i]) continue;
    const glm::ivec3 cell = layout.volume_bricks[size_t(layout.mine[i])].cell;
    const IndexBox& box = d.boxes[i];
    const glm::ivec3 n = box.size();
    auto owns = [&](int a, double p) {
      const std::vector<double>& planes = layout.planes[size_t(a)];
      const int c = cell[a], last = int(planes.size()) - 2;
      return (c == 0 || p >= planes[size_t(c)]) && (c == last || p < planes[size_t(c) + 1]);
    };
    const std::vector<float>& samples = d.samples[i];
    for (int z = 0; z < n.z; ++z) {
      if (!owns(2, d.grid.worldOfIndex(glm::dvec3(0, 0, box.lo.z + z)).z)) continue;
      for (int y = 0; y < n.y; ++y) {
        if (!owns(1, d.grid.worldOfIndex(glm::dvec3(0, box.lo.y + y, 0)).y)) continue;
        for (int x = 0; x < n.x; ++x) {
          if (!owns(0, d.grid.worldOfIndex(glm::dvec3(box.lo.x + x, 0, 0)).x)) continue;
          const int bin = binner.binOf(samples[(size_t(z) * size_t(n.y) + size_t(y)) * size_t(n.x) + size_t(x)]);
          if (bin >= 0) ++bins[size_t(bin)];
        }
      }
    }
  }
  return bins;
}

}  // namespace

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
    d.histogram = ValueHistogram::framing(spec.transfer, d.data_min, d.data_max);
    std::vector<long long> mine = countOwnSamples(d, layout, HistogramBinner(d.histogram));
    d.histogram.counts.assign(kHistogramBins, 0);
    MPI_Reduce(mine.data(), d.histogram.counts.data(), kHistogramBins, MPI_LONG_LONG, MPI_SUM, 0, comm);
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    if (rank != 0) d.histogram.counts.clear();
  }
  return out;
}

std::vector<TransferFunction> fieldTransfers(const std::vector<FieldSpec>& fields,
                                             const std::vector<FieldStep>& data) {
  std::vector<TransferFunction> out;
  for (size_t f = 0; f < fields.size(); ++f)
    out.push_back(fields[f].shownTransfer().build(data[f].data_min, data[f].data_max,
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
