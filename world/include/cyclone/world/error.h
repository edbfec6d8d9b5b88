// The error every World API call throws on bad input: cyclone::InvalidArgument, shared
// with the dynamics core.
#pragma once

#include "cyclone/error.h"
