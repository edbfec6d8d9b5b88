/// \file
/// Everything a user of the World layer needs: the World, its settings, shapes, stats,
/// events, queries, debug drawing and the game loop's FixedStepper.
#pragma once

#include "cyclone/body.h"
#include "cyclone/world/contact_listener.h"
#include "cyclone/world/debug_draw.h"
#include "cyclone/world/error.h"
#include "cyclone/world/events.h"
#include "cyclone/world/game_loop.h"
#include "cyclone/world/queries.h"
#include "cyclone/world/settings.h"
#include "cyclone/world/shape.h"
#include "cyclone/world/stats.h"
#include "cyclone/world/world.h"
