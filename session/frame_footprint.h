#pragma once
// What `compositing.strategy: auto` forecasts a frame from (compositing/strategy_model.h): each
// rank's bricks projected on the screen, from the layout and camera alone, so every rank computes
// the same footprint before any brick is rendered. An upper bound: a brick's box, not what in it
// shows (a brick that turns out empty still counts).
#include "common/camera.h"
#include "compositing/strategy_model.h"
#include "session/session_layout.h"

namespace sortlast {

FrameFootprint forecastFootprint(const SessionLayout& layout, const Camera& cam, int ranks);

}  // namespace sortlast
