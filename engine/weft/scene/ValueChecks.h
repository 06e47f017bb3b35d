#pragma once
// The checks of the scene's numeric values that a task parameter may change (density, stiffness,
// friction, wind), in one place: SceneLoader reads the file through them and the typed parameter
// setters (diff/SceneParameter.h) check a new value through them, so a value out of range is
// refused with the same `<file>: <path>: <what>` either way. Each takes the reader of the value's
// node, as the loader sees it.

#include <weft/core/Types.h>
#include <weft/scene/JsonReader.h>

namespace weft {

// Stretch and bending stiffness and attachment weights above this are input errors.
inline constexpr double kMaxStiffness = 1e12;

double readDensity(const JsonReader& r);              // > 0 (kg/m^2)
double readStiffness(const JsonReader& r);            // [0, kMaxStiffness] (stretch, bend)
double readAttachmentStiffness(const JsonReader& r);  // (0, kMaxStiffness] (N/m per vertex)
double readFriction(const JsonReader& r);             // [0, 1e3]
double readWindStrength(const JsonReader& r);         // [-1e6, 1e6] (N/m^2)
double readWindFrequency(const JsonReader& r);        // [0, 1e6] (Hz)
double readWindPhase(const JsonReader& r);            // [-1e6, 1e6] (rad)
Vec3 readWindDirection(const JsonReader& r);          // any nonzero vector, used as given

}  // namespace weft
