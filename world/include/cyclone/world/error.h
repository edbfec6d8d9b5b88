/// \file
/// The error every World API call throws on bad input: cyclone::InvalidArgument, shared
/// with the dynamics core (cyclone/error.h).
#pragma once

#include "cyclone/error.h"
