// The viewer's colours: what a body's colour says about its state, the sky and the ground.
// GL-free, so that tests can tell them apart in a screenshot.
#pragma once

#include "session.h"

namespace cyclone::viewer {

/// A colour: red, green, blue, each in [0, 1].
struct Rgb {
    float r = 1, g = 1, b = 1;
};

/// The colour the picture is cleared to.
inline constexpr Rgb kSkyColor{0.62f, 0.74f, 0.86f};
/// Planes (the ground) and their grid lines.
inline constexpr Rgb kGroundColor{0.80f, 0.79f, 0.74f};
inline constexpr Rgb kGridColor{0.5f, 0.52f, 0.5f};
/// Springs, the scene's and the mouse's.
inline constexpr Rgb kSpringColor{0.95f, 0.95f, 0.95f};

/// The colour of each BodyState, before lighting.
inline constexpr Rgb stateColor(BodyState state) {
    switch (state) {
    case BodyState::Static: return Rgb{0.60f, 0.60f, 0.63f};
    case BodyState::Awake: return Rgb{0.95f, 0.55f, 0.20f};
    case BodyState::Asleep: return Rgb{0.35f, 0.42f, 0.80f};
    case BodyState::NonFinite: return Rgb{0.95f, 0.10f, 0.10f};
    case BodyState::Kinematic: return Rgb{0.55f, 0.80f, 0.35f};
    case BodyState::Sensor: return Rgb{0.30f, 0.85f, 0.85f};
    }
    return Rgb{};
}

}  // namespace cyclone::viewer
