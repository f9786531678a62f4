#pragma once
// The in-situ actions file: what to render, when, and where to put it (docs/insitu_actions.md).
// It is read once, when the simulation constructs sortlast::InSitu, and checked completely there,
// so a typo fails at startup with a message instead of hours later at the first trigger.
#include <optional>
#include <string>
#include <vector>

namespace sortlast {

// When a render fires. Both parts may be given; then either fires it.
struct Trigger {
  int every = 0;                  // > 0: on steps divisible by it
  std::string when;               // non-empty: a quantity the simulation publishes ...
  std::optional<double> crosses;  // ... fires the step it crosses this value
  // every 0 and no `when`: every step.
};

// A Cinema "spec A" image database: one image per (phi, theta) per fired step (insitu/cinema.h).
struct CinemaSpec {
  std::string directory;           // holds info.json and one folder per step
  std::vector<double> phi, theta;  // degrees; phi in [0, 360), theta in (-90, 90), each unique
};

struct RenderAction {
  std::string name;    // [a-zA-Z0-9_-]+, unique among the renders
  std::string output;  // image pattern with {step} (insitu/output_names.h); empty: cinema only
  Trigger trigger;
  // key.path=VALUE (the value as YAML flow text), frame keys only, from `scene:`; the session's
  // request keys (session/render_session.h FrameRequest::overrides).
  std::vector<std::string> overrides;
  std::optional<CinemaSpec> cinema;
};

struct Actions {
  bool abort_on_error = false;  // on_error: abort
  std::string serve;            // live view address (host:port), empty: none
  std::string serve_token;
  // The session's GL backend and device (scene keys render.backend, render.device; docs/cluster.md):
  // the only session-wide scene keys an actions file sets, as "key=value" overrides.
  std::vector<std::string> session_overrides;
  std::vector<RenderAction> renders;
};

// Parses and checks the whole file; `source_name` (the file's name) starts every message. Throws
// InputError naming the key at fault (and its line), for unknown keys, bad values, and scene keys
// that the simulation's data fixes. The scene keys are also checked by the scene parser, so a bad
// value fails here rather than at the first render.
Actions parseActions(const std::string& yaml_text, const std::string& source_name);

}  // namespace sortlast
