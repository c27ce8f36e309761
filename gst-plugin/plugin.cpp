// The gesturecam plugin: registers its elements.
#include "gsthandoverlay.hpp"
#include "gsthandscenesrc.hpp"
#include "gsthandtracker.hpp"
#include "gstimagesizelimit.hpp"

#include <gst/gst.h>

static gboolean plugin_init(GstPlugin* plugin)
{
    gboolean ok = FALSE;
    ok |= GST_ELEMENT_REGISTER(handtracker, plugin);
    ok |= GST_ELEMENT_REGISTER(handscenesrc, plugin);
    ok |= GST_ELEMENT_REGISTER(imagesizelimit, plugin);
    ok |= GST_ELEMENT_REGISTER(handoverlay, plugin);
    return ok;
}

GST_PLUGIN_DEFINE(GST_VERSION_MAJOR, GST_VERSION_MINOR, gesturecam,
                  "Stereo tracking of a pointing hand (CONDENSATION) for conferencing pipelines", plugin_init,
                  GC_PLUGIN_VERSION, GC_PLUGIN_LICENSE, GC_PLUGIN_PACKAGE, GC_PLUGIN_ORIGIN)
