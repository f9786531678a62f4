// Several fields (the `volumes` key): parsing and its errors (scene/sections/volumes.cpp), the grid
// the layout cuts (scene/fields_scene.h), each field's part of a brick and its block ranges
// (render/volume/field_bricks.h), and the mixture's reference with one field against the
// one-field reference (reference/fields_reference.h).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "common/trilinear.h"
#include "io/volume_source.h"
#include "reference/fields_reference.h"
#include "render/volume/field_bricks.h"
#include "scene/scene.h"
#include "tests/unit/input_error_of.h"

namespace sortlast {
namespace {

Scene parse(const std::string& yaml, const std::vector<std::string>& overrides = {}) {
  return parseScene(SceneText{"/nonexistent/fields_test.yaml", yaml}, overrides);
}

const char* kTwo = R"(
volumes:
  - procedural: sphere
    dims: [24, 20, 16]
    spacing: [1, 1, 1.5]
    transfer: {colormap: viridis, range: [0, 1]}
  - procedural: blobs
    dims: [40, 12, 30]
    spacing: [0.5, 2, 1]
    transfer:
      points: [[0, 1, 0, 0, 0], [1, 1, 0, 0, 0.5]]
)";

TEST(FieldsScene, TwoEntriesEachWithItsGridAndTransfer) {
  const Scene s = parse(kTwo);
  ASSERT_EQ(s.fields.size(), 2u);
  EXPECT_TRUE(s.hasFields());
  EXPECT_EQ(s.fields[0].name, "volumes[0]");
  EXPECT_EQ(s.fields[1].name, "volumes[1]");
  EXPECT_EQ(s.fields[0].volume.procedural, "sphere");
  EXPECT_EQ(s.fields[1].volume.grid.dims, glm::ivec3(40, 12, 30));
  EXPECT_EQ(s.fields[1].volume.grid.spacing, glm::dvec3(0.5, 2, 1));
  EXPECT_EQ(s.fields[0].transfer.colormap, "viridis");
  ASSERT_TRUE(s.fields[0].transfer.range.has_value());
  EXPECT_FALSE(s.fields[1].transfer.range.has_value());
  ASSERT_EQ(s.fields[1].transfer.points.size(), 2u);
  EXPECT_DOUBLE_EQ(s.fields[1].transfer.points[1].a, 0.5);
  // The first field is the scene's volume and transfer function too.
  EXPECT_EQ(s.volume.procedural, "sphere");
  EXPECT_EQ(s.transfer.colormap, "viridis");
  // No pre-integration with several fields, even where `auto` would pick it.
  EXPECT_FALSE(s.fields[1].transfer.preintegrated);
  EXPECT_FALSE(s.transfer.preintegrated);
}

TEST(FieldsScene, VolumeGivenTooIsTheFirstField) {
  const Scene s = parse(R"(
volume: {procedural: marschner_lobb, dims: [16, 16, 16]}
transfer: {preset: ramp}
volumes:
  - {procedural: sphere, dims: [8, 8, 8], spacing: [3, 3, 3]}
)");
  ASSERT_EQ(s.fields.size(), 2u);
  EXPECT_EQ(s.fields[0].name, "volume");
  EXPECT_EQ(s.fields[0].volume.procedural, "marschner_lobb");
  EXPECT_EQ(s.fields[1].volume.procedural, "sphere");
}

// `volumes[i].key` overrides (--set, service requests): into entry i; an entry's `visible`.
TEST(FieldsScene, EntryKeysAreSetByIndex) {
  const Scene s = parse(kTwo, {"volumes[1].transfer.points=[[0, 0, 1, 0, 0], [1, 0, 1, 0, 0.25]]",
                               "volumes[1].transfer.colormap=\"\"", "volumes[0].visible=false",
                               "volumes[0].transfer.range=[0.2, 0.8]"});
  ASSERT_EQ(s.fields.size(), 2u);
  ASSERT_EQ(s.fields[1].transfer.points.size(), 2u);
  EXPECT_DOUBLE_EQ(s.fields[1].transfer.points[1].a, 0.25);
  EXPECT_DOUBLE_EQ(s.fields[1].transfer.points[1].g, 1.0);
  EXPECT_TRUE(s.fields[1].visible);
  EXPECT_FALSE(s.fields[0].visible);
  ASSERT_TRUE(s.fields[0].transfer.range.has_value());
  EXPECT_DOUBLE_EQ(s.fields[0].transfer.range->first, 0.2);
  EXPECT_EQ(s.fields[0].transfer.colormap, "viridis");  // the rest of the entry's map stays
  // Hidden: every point of the transfer function drawn at opacity 0, colours kept.
  const TransferSpec shown = s.fields[0].shownTransfer();
  ASSERT_EQ(shown.points.size(), s.fields[0].transfer.points.size());
  for (size_t i = 0; i < shown.points.size(); ++i) {
    EXPECT_EQ(shown.points[i].a, 0.0);
    EXPECT_EQ(shown.points[i].r, s.fields[0].transfer.points[i].r);
  }
  EXPECT_GT(s.fields[0].transfer.points.back().a, 0.0);
  // In the scene file too.
  const Scene f = parse(R"(
volumes:
  - {procedural: sphere, dims: [8, 8, 8]}
  - {procedural: blobs, dims: [8, 8, 8], visible: false}
)");
  EXPECT_TRUE(f.fields[0].visible);
  EXPECT_FALSE(f.fields[1].visible);
}

TEST(FieldsScene, BadEntryKeysAreNamed) {
  auto error = [](const std::vector<std::string>& overrides, const char* yaml = kTwo) {
    return inputErrorOf([&] { parse(yaml, overrides); });
  };
  EXPECT_NE(error({"volumes[2].transfer.points=[[0,1,1,1,1],[1,1,1,1,1]]"}).find("'volumes[2].transfer.points': the scene's volumes list has 2 entries"),
            std::string::npos);
  EXPECT_NE(error({"volumes[1].transfer.colour=x"}).find("unknown scene key 'volumes[1].transfer.colour'"), std::string::npos);
  EXPECT_NE(error({"volumes[1].visible=maybe"}).find("'volumes[1].visible': expected true or false"), std::string::npos);
  EXPECT_NE(error({"volumes[1].dims=[0, 4, 4]"}).find("volumes[1].dims"), std::string::npos);
  EXPECT_NE(error({"volumes[0].transfer.points=[[0,1,1,1,1],[1,1,1,1,1]]"}, "volume: {procedural: sphere}\n")
                .find("the scene's volumes list has 0 entries"),
            std::string::npos);
  EXPECT_NE(error({}, "volumes:\n  - {procedural: sphere, dims: [8, 8, 8], visible: false}\n").find("volumes[0].visible"),
            std::string::npos);
  // Not an entry key: the name is a scene key's or unknown.
  EXPECT_FALSE(parseFieldEntryKey("volumes.1.transfer.points"));
  EXPECT_FALSE(parseFieldEntryKey("volumes[-1].visible"));
  EXPECT_FALSE(parseFieldEntryKey("volumes[1]"));
  EXPECT_FALSE(parseFieldEntryKey("volumes[1]."));
  EXPECT_FALSE(parseFieldEntryKey("volumes[99999999].visible"));
  ASSERT_TRUE(parseFieldEntryKey("volumes[12].transfer.points"));
  EXPECT_EQ(parseFieldEntryKey("volumes[12].transfer.points")->entry, 12u);
  EXPECT_EQ(parseFieldEntryKey("volumes[12].transfer.points")->path(), (std::vector<std::string>{"transfer", "points"}));
}

// A request may change an entry's transfer map and visibility, nothing else of it.
TEST(FieldsScene, EntryFrameKeys) {
  for (const char* k : {"volumes[0].transfer.points", "volumes[3].transfer.colormap", "volumes[1].transfer.range",
                        "volumes[1].transfer.scale", "volumes[1].visible"})
    EXPECT_TRUE(isFrameKey(k)) << k;
  for (const char* k : {"volumes", "volumes[1].dims", "volumes[1].file", "volumes[1].procedural",
                        "volumes[1].spacing", "volumes[1].transfer", "volumes[1].transfer.nonsense"})
    EXPECT_FALSE(isFrameKey(k)) << k;
}

TEST(FieldsScene, OneEntryIsTheVolumeForm) {
  const Scene a = parse(R"(
volumes:
  - procedural: sphere
    dims: [20, 30, 10]
    spacing: [1, 0.5, 2]
    transfer: {preset: sharp, colormap: inferno, table_size: 512}
)");
  const Scene b = parse(R"(
volume: {procedural: sphere, dims: [20, 30, 10], spacing: [1, 0.5, 2]}
transfer: {preset: sharp, colormap: inferno, table_size: 512}
)");
  EXPECT_FALSE(a.hasFields());
  EXPECT_EQ(a.volume.procedural, b.volume.procedural);
  EXPECT_EQ(a.volume.grid.dims, b.volume.grid.dims);
  EXPECT_EQ(a.volume.grid.spacing, b.volume.grid.spacing);
  EXPECT_EQ(a.transfer.table_size, b.transfer.table_size);
  EXPECT_EQ(a.transfer.preintegrated, b.transfer.preintegrated);  // auto alike (sharp: on)
  EXPECT_TRUE(a.transfer.preintegrated);
  ASSERT_EQ(a.transfer.points.size(), b.transfer.points.size());
  for (size_t i = 0; i < a.transfer.points.size(); ++i) {
    EXPECT_EQ(a.transfer.points[i].value, b.transfer.points[i].value);
    EXPECT_EQ(a.transfer.points[i].r, b.transfer.points[i].r);
    EXPECT_EQ(a.transfer.points[i].a, b.transfer.points[i].a);
  }
}

TEST(FieldsScene, ErrorsNameTheEntryAndKey) {
  auto entry1 = [](const std::string& second) {
    return "volumes:\n  - {procedural: sphere}\n  - " + second + "\n";
  };
  std::string e = inputErrorOf([&] { parse(entry1("{procedural: sphere, dimz: [8, 8, 8]}")); });
  EXPECT_NE(e.find("unknown scene key 'volumes[1].dimz'"), std::string::npos) << e;
  e = inputErrorOf([&] { parse(entry1("{procedural: sphere, dims: [1, 8, 8]}")); });
  EXPECT_NE(e.find("scene key 'volumes[1].dims'"), std::string::npos) << e;
  e = inputErrorOf([&] { parse(entry1("{procedural: sphere, type: int7}")); });
  EXPECT_NE(e.find("volumes[1].type"), std::string::npos) << e;
  e = inputErrorOf([&] { parse(entry1("{procedural: sphere, transfer: {range: [1, 0]}}")); });
  EXPECT_NE(e.find("scene key 'volumes[1].transfer.range'"), std::string::npos) << e;
  e = inputErrorOf([&] { parse(entry1("{procedural: sphere, transfer: {ponts: []}}")); });
  EXPECT_NE(e.find("unknown scene key 'volumes[1].transfer.ponts'"), std::string::npos) << e;
  e = inputErrorOf([&] { parse(entry1("{procedural: sphere, transfer: {points: [[0, 1]]}}")); });
  EXPECT_NE(e.find("scene key 'volumes[1].transfer.points'"), std::string::npos) << e;
  e = inputErrorOf([&] { parse(entry1("{procedural: none}")); });
  EXPECT_NE(e.find("volumes[1].procedural"), std::string::npos) << e;
  e = inputErrorOf([&] { parse(entry1("{files: 'a_*.raw'}")); });
  EXPECT_NE(e.find("volumes[1].files"), std::string::npos) << e;
  e = inputErrorOf([&] { parse(entry1("[1, 2]")); });
  EXPECT_NE(e.find("scene key 'volumes[1]'"), std::string::npos) << e;
  e = inputErrorOf([&] { parse("volumes: {procedural: sphere}\n"); });
  EXPECT_NE(e.find("scene key 'volumes'"), std::string::npos) << e;
  e = inputErrorOf([&] { parse("transfer: {preset: ramp}\nvolumes: [{procedural: sphere}]\n"); });
  EXPECT_NE(e.find("scene key 'transfer'"), std::string::npos) << e;
  e = inputErrorOf([&] {
    parse("volumes: [{procedural: sphere}, {procedural: sphere}, {procedural: sphere}, "
          "{procedural: sphere}, {procedural: sphere}]\n");
  });
  EXPECT_NE(e.find("at most 4"), std::string::npos) << e;
}

TEST(FieldsScene, ModesItCannotMixAreRefusedByName) {
  const std::string two = "volumes: [{procedural: sphere}, {procedural: blobs, dims: [8, 8, 8]}]\n";
  // (`c` by name, not a structured binding: clang 14 cannot capture a binding in a lambda.)
  for (const auto& c : std::vector<std::pair<std::string, std::string>>{
           {"render.method=slicing", "render.method"},
           {"adaptive.tolerance=1", "adaptive.tolerance"},
           {"render.adaptive_step=true", "render.adaptive_step"},
           {"render.shading=true", "render.shading"},
           {"particles.procedural=layers", "particles"}}) {
    const std::string e = inputErrorOf([&] { parse(two, {c.first}); });
    EXPECT_NE(e.find("'volumes' and '" + c.second), std::string::npos) << c.first << ": " << e;
  }
  const std::string e = inputErrorOf([&] {
    parse("volumes: [{procedural: sphere}, {procedural: blobs, transfer: {preintegrated: true}}]\n");
  });
  EXPECT_NE(e.find("volumes[1].transfer.preintegrated"), std::string::npos) << e;
  // One field through volumes renders as `volume` does: nothing refused.
  EXPECT_NO_THROW(parse("volumes: [{procedural: sphere}]\n", {"render.method=slicing"}));
}

TEST(FieldsScene, MessagesRenameKeysNotProse) {
  EXPECT_EQ(fieldMessage("scene key 'volume.dims': bad; see transfer.range", "volumes[2]"),
            "scene key 'volumes[2].dims': bad; see volumes[2].transfer.range");
  EXPECT_EQ(fieldMessage("outside the volume. Then", "volumes[2]"), "outside the volume. Then");
  EXPECT_EQ(fieldMessage("scene key 'volume.dims'", "volume"), "scene key 'volume.dims'");
}

TEST(FieldsGrid, CoversEveryFieldWithTheFinestSpacing) {
  const Scene s = parse(kTwo);
  const GridGeometry g = fieldsGrid(s.fields);
  EXPECT_EQ(g.spacing, glm::dvec3(0.5, 1, 1));
  const Box3 all = g.worldBox();
  for (const FieldSpec& f : s.fields) {
    const Box3 b = f.volume.grid.worldBox();
    for (int a = 0; a < 3; ++a) {
      EXPECT_LE(all.lo[a], b.lo[a]);
      EXPECT_GE(all.hi[a], b.hi[a]);
    }
  }
  // No cell more than needed: x spans 23 (field 0) and 19.5 (field 1): 46 cells of 0.5.
  EXPECT_EQ(g.dims.x, 47);
  EXPECT_EQ(g.dims.z, 30);  // z: 15 * 1.5 = 22.5 and 29: 29 cells of 1
}

// Trilinear value of a whole field at world point p.
double fieldAt(const GridGeometry& g, const std::vector<float>& s, const glm::dvec3& p) {
  WholeVolume w{g, s};
  return w.at(g.indexOfWorld(p));
}

TEST(FieldBricks, PartAndBlockRangesHoldEveryValueInTheBlock) {
  const GridGeometry g{{13, 9, 11}, {0.7, 1.3, 0.9}};
  VolumeDesc d;
  d.procedural = "blobs";
  d.grid = g;
  const std::vector<float> whole = readWholeVolume(d);
  // A box poking out of the field on x and z, inside on y.
  const Box3 world{{-2.0, -3.1, 1.0}, {9.0, 2.0, 8.0}};
  bool present = false;
  const IndexBox box = fieldBoxOf(g, world, present);
  ASSERT_TRUE(present);
  EXPECT_EQ(box.hi.x, 12);
  EXPECT_EQ(box.hi.z, 10);
  const std::vector<float> part = extractBox(whole, g.dims, box);
  FieldBrickPart p{0, g, box, &part};
  std::array<std::vector<double>, 3> planes;
  for (int a = 0; a < 3; ++a)
    for (int i = 0; i <= 3; ++i) planes[a].push_back(world.lo[a] + (world.hi[a] - world.lo[a]) * i / 3.0);
  std::vector<float> vmin, vmax;
  fieldBlockRanges(p, planes, vmin, vmax);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const Box3 field = g.worldBox();
  int inside = 0;
  for (int z = 0; z < 3; ++z)
    for (int y = 0; y < 3; ++y)
      for (int x = 0; x < 3; ++x) {
        const size_t i = size_t(x) + 3 * (size_t(y) + 3 * size_t(z));
        for (int k = 0; k < 200; ++k) {
          const glm::dvec3 q{planes[0][x] + u(rng) * (planes[0][x + 1] - planes[0][x]),
                             planes[1][y] + u(rng) * (planes[1][y + 1] - planes[1][y]),
                             planes[2][z] + u(rng) * (planes[2][z + 1] - planes[2][z])};
          if (!field.contains(q)) continue;
          ++inside;
          const double v = fieldAt(g, whole, q);
          EXPECT_GE(v, vmin[i] - 1e-6) << x << y << z;
          EXPECT_LE(v, vmax[i] + 1e-6) << x << y << z;
        }
      }
  EXPECT_GT(inside, 1000);
  // A block wholly outside the field has no range.
  const Box3 away{{20.0, 0.0, 0.0}, {21.0, 1.0, 1.0}};
  fieldBoxOf(g, away, present);
  EXPECT_FALSE(present);
}

TEST(FieldsReference, OneFieldIsTheOneFieldReference) {
  VolumeDesc d;
  d.procedural = "marschner_lobb";
  d.grid = {{17, 13, 15}, {1.0, 1.3, 0.8}};
  WholeVolume vol{d.grid, readWholeVolume(d)};
  const TransferFunction tf(TransferFunction::preset("default"), 0.0, 1.0, 0.8);
  Camera cam;
  cam.position = {20, 14, 30};
  cam.width = cam.height = 24;
  const ImageF one = renderReference(vol, tf, cam, 0.1, 2, {});
  const ImageF mixed = renderFieldsReference({{vol, tf}}, d.grid.worldBox(), cam, 0.1, 2, {});
  double worst = 0, sum = 0;
  for (size_t i = 0; i < one.px.size(); ++i) {
    worst = std::max(worst, double(std::abs(one.px[i] - mixed.px[i])));
    sum += one.px[i];
  }
  EXPECT_LT(worst, 1e-6);  // tau c / tau = c within a double rounding, then float
  EXPECT_GT(sum, 1.0);     // not an empty image
}

// Clipped and orthographic: the same rays (Camera::pixelRay) and the same cut (clipSpan) as the
// one-field reference, whose clipping and parallel rays its own tests check.
TEST(FieldsReference, ClippedOrthographicIsTheOneFieldReference) {
  VolumeDesc d;
  d.procedural = "marschner_lobb";
  d.grid = {{17, 13, 15}, {1.0, 1.3, 0.8}};
  WholeVolume vol{d.grid, readWholeVolume(d)};
  const TransferFunction tf(TransferFunction::preset("default"), 0.0, 1.0, 0.8);
  ClipRegion clip;
  clip.planes.push_back({{1.0, 0.4, -0.3}, 0.5});
  clip.has_box = true;
  clip.box = {{-9, -9, -4}, {9, 9, 9}};
  vol.clip = clip;
  Camera cam;
  cam.position = {20, 14, 30};
  cam.projection = Projection::kOrthographic;
  cam.parallel_scale = 9.0;
  cam.width = cam.height = 24;
  const ImageF one = renderReference(vol, tf, cam, 0.1, 2, {});
  const ImageF mixed = renderFieldsReference({{vol, tf}}, d.grid.worldBox(), cam, 0.1, 2, clip);
  vol.clip = {};
  const ImageF whole = renderFieldsReference({{vol, tf}}, d.grid.worldBox(), cam, 0.1, 2, {});
  double worst = 0, sum = 0, cut = 0;
  for (size_t i = 0; i < one.px.size(); ++i) {
    worst = std::max(worst, double(std::abs(one.px[i] - mixed.px[i])));
    cut = std::max(cut, double(std::abs(whole.px[i] - mixed.px[i])));
    sum += one.px[i];
  }
  EXPECT_LT(worst, 1e-6);
  EXPECT_GT(sum, 1.0);   // not an empty image
  EXPECT_GT(cut, 0.05);  // and the clip region cuts something away
}

// Two fields where each is alone: the mixture is each one's own reference where the other is
// absent; and two copies of one field are that field with twice its extinction.
TEST(FieldsReference, TwoCopiesDoubleTheExtinction) {
  VolumeDesc d;
  d.procedural = "sphere";
  d.grid = {{11, 11, 11}, {1.0, 1.0, 1.0}};
  WholeVolume vol{d.grid, readWholeVolume(d)};
  const std::vector<TfPoint> pts{{0, 1, 0.5, 0.2, 0.0}, {1, 1, 0.5, 0.2, 0.3}};
  const TransferFunction tf(pts, 0.0, 1.0, 1.0);
  Camera cam;
  cam.position = {0, 0, 25};
  cam.width = cam.height = 9;
  const ImageF two = renderFieldsReference({{vol, tf}, {vol, tf}}, d.grid.worldBox(), cam, 0.05, 1, {});
  const ImageF one = renderFieldsReference({{vol, tf}}, d.grid.worldBox(), cam, 0.05, 1, {});
  // Centre pixel: alpha_two = 1 - (1 - alpha_one)^2 exactly in the continuous model.
  const size_t c = (4 * 9 + 4) * 4 + 3;
  EXPECT_GT(one.px[c], 0.1);
  EXPECT_NEAR(two.px[c], 1.0 - (1.0 - one.px[c]) * (1.0 - one.px[c]), 1e-5);
}

}  // namespace
}  // namespace sortlast
