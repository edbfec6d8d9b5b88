// Everything a user of the World layer needs.
#pragma once

#include "cyclone/body.h"
#include "cyclone/world/error.h"
#include "cyclone/world/settings.h"
#include "cyclone/world/shape.h"
#include "cyclone/world/stats.h"
#include "cyclone/world/world.h"
