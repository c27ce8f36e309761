#include "target_plane_property.hpp"

#include <gst/gst.h>

#include <array>
#include <cmath>

namespace gc::gst {

GParamSpec* target_plane_param_spec(guint flags)
{
    return gst_param_spec_array(
        "target-plane", "Target plane",
        "A plane of the room that pointing designates, such as a wall or a table: <a, b, c, d> for "
        "a x + b y + c z + d = 0 in the head frame (mm; x right, y down, z ahead of the head at rest), "
        "e.g. <0, 0, 1, -3000> for a wall 3 m ahead. A held pointing's target is where its ray meets it, or "
        "target-distance along the ray when the ray runs away from it; <>: none",
        g_param_spec_double("coefficient", "Coefficient", "One of a, b, c, d", -G_MAXDOUBLE, G_MAXDOUBLE, 0.0,
                            GParamFlags(G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS)),
        GParamFlags(flags));
}

void set_target_plane(std::optional<Plane>& plane, const GValue* value)
{
    const guint n = gst_value_array_get_size(value);
    if (n == 0) {
        plane.reset();
        return;
    }
    std::array<double, 4> c{NAN, NAN, NAN, NAN};
    for (guint i = 0; i < n && i < c.size(); ++i) {
        GValue number = G_VALUE_INIT;
        g_value_init(&number, G_TYPE_DOUBLE);
        if (g_value_transform(gst_value_array_get_value(value, i), &number)) c[i] = g_value_get_double(&number);
        g_value_unset(&number);
    }
    const std::optional<Plane> given = n == 4 ? plane_from_coefficients(c[0], c[1], c[2], c[3]) : std::nullopt;
    if (!given) {
        g_warning("handtracker: target-plane takes <a, b, c, d>, four finite numbers with a, b, c not all zero, "
                  "or <> for none; %u value(s) given, the plane stays as it was",
                  n);
        return;
    }
    plane = given;
}

void get_target_plane(const std::optional<Plane>& plane, GValue* value)
{
    if (!plane) return;
    const std::array<double, 4> c{plane->normal.x(), plane->normal.y(), plane->normal.z(), plane->d};
    for (double coefficient : c) {
        GValue number = G_VALUE_INIT;
        g_value_init(&number, G_TYPE_DOUBLE);
        g_value_set_double(&number, coefficient);
        gst_value_array_append_and_take_value(value, &number);
    }
}

}  // namespace gc::gst
