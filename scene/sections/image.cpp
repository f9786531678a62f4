// The image section's keys: the image: size, background and colour legend; and a movie output's.
#include "scene/key_rows.h"

std::vector<sortlast::SceneKey> sortlast::imageKeys() {
  // Checked by parseScene with both sizes in the message.
  const Check kImageSize{"in [1, 32768]", nullptr};
  return {
    {"image.width", "512", "Image width in pixels.",
     Int{member<&Scene::camera, &Camera::width>, {kImageSize}}},
    {"image.height", "512", "Image height in pixels.",
     Int{member<&Scene::camera, &Camera::height>, {kImageSize}}},
    {"image.background", "[0, 0, 0]",
     "Colour the frame is composited over when written (premultiplied images stay exact).",
     Vector<glm::dvec3>{member<&Scene::image, &ImageSection::background>}},
    {"image.legend.position", "none",
     "Colour legend drawn into written frames (rank 0, after compositing): `none`, `right`, "
     "`left`, `bottom` or `top`. A bar of the transfer function's colours (plain, not weighted "
     "by opacity) over `transfer.range`, with tick labels in the data's units placed in "
     "`transfer.scale` (decades, 1e2 1e3, under `log`). Text in DejaVu Sans through FreeType "
     "(Debian's fonts-dejavu-core); the viewer draws the same legend over its image.",
     Choice{Field<LegendPosition>([](Scene& s) -> LegendPosition& { return s.image.legend.position; })}},
    {"image.legend.title", "\"\"", "The legend's title (empty: none).",
     Text{[](Scene& s) -> std::string& { return s.image.legend.title; }}},
    {"image.legend.ticks", "5", "About how many labelled ticks the legend's bar has.",
     Int{[](Scene& s) -> int& { return s.image.legend.ticks; }, {{"in [2, 20]"}}}},
    {"image.legend.units", "\"\"", "Units after the legend's title, in brackets (empty: none).",
     Text{[](Scene& s) -> std::string& { return s.image.legend.units; }}},
    {"movie.frame_rate", "30",
     "Frames per second of a movie output (`-o NAME.mp4`: H.264 through libx264; `NAME.webm`: "
     "VP9 through libvpx).",
     Int{[](Scene& s) -> int& { return s.image.movie.frame_rate; }, {{"in [1, 240]"}}}},
    {"movie.quality", "auto",
     "A movie's constant rate factor, lower is better: H.264 takes 0-51 (0 lossless; `auto`: 23, "
     "libx264's default), VP9 0-63 (libvpx's constant-quality mode; `auto`: 31).",
     OptionalReal{[](Scene& s) -> std::optional<double>& { return s.image.movie.quality; },
                  {{"in [0, 63]"}}},
     AutoValue{}},
  };
}
