#pragma once
// The time steps inside one data file: the records of a 4-D NetCDF variable, or the datasets of an
// HDF5 `volume.dataset` with `{step}`. Only the file's metadata says how many there are, and
// parsing reads no data file (scene/scene.h): the code that loads a scene resolves them, on every
// rank alike, before any rank loads data (the session, `sortlast reference`, `adaptive-stats`).
#include "scene/scene.h"

namespace sortlast {

// Whether the scene's volume holds its time steps inside one file (NetCDF volume.file without
// volume.files: it may; an HDF5 volume.dataset with {step}: it does).
bool hasFileSteps(const Scene& s);

// Reads the file's metadata: sets time.steps, checks time.step against it (and a particles.files
// series against it, and the glow emitters' rates over every frame), and points the volume at
// the step (its NetCDF record, its HDF5 dataset). Nothing for a scene without steps in a file;
// a second call changes nothing. Throws InputError naming the file and the key.
void resolveFileSteps(Scene& s);

}  // namespace sortlast
