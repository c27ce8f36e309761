// handtracker's `target-plane`: a plane of the room, such as a wall or a table, given as the
// four coefficients <a, b, c, d> of a x + b y + c z + d = 0 in the head frame (millimetres),
// or <> for none. A held pointing's target is where its ray meets the plane.
#pragma once

#include "stereo/ray_geometry.hpp"

#include <glib-object.h>

#include <optional>

namespace gc::gst {

// The property's GParamSpec: a GstValueArray of doubles.
GParamSpec* target_plane_param_spec(guint flags);
// Stores `value` (a GstValueArray) as the plane. Anything but <> or four finite numbers with
// a non-zero (a, b, c) is refused with a warning, and the plane stays as it was.
void set_target_plane(std::optional<Plane>& plane, const GValue* value);
// The plane as the property reads back: its coefficients with (a, b, c) of unit length.
void get_target_plane(const std::optional<Plane>& plane, GValue* value);

}  // namespace gc::gst
