#include "handtracker_director.hpp"

#include "head_connection.hpp"
#include "head_uri_property.hpp"

#include "headctl/uri.hpp"

#include <algorithm>
#include <exception>
#include <memory>
#include <string>

#define GST_CAT_DEFAULT gst_hand_tracker_debug

namespace gc::gst {

namespace {

bool ensure_director(GstHandTracker* self, const TrackerSettings& settings)
{
    TrackerState& e = *self->state;
    if (e.director) return true;
    if (e.director_failed) return false;
    gc::headctl::DirectorCameraConfig config;
    config.uri = settings.director;
    config.token = e.director_token;
    if (e.calibration && e.calibration->director) config.mount = *e.calibration->director;
    config.region_mm = settings.target_region_mm;
    config.manual_pause_s = settings.manual_pause_s;
    if (settings.director_home_preset >= 0) config.home_preset = settings.director_home_preset;
    config.clock = element_clock(GST_ELEMENT(self));
    config.on_state_change = connection_reporter(GST_ELEMENT(self), settings.director);
    config.on_command = command_logger(GST_ELEMENT(self));
    try {
        e.director = std::make_unique<gc::headctl::DirectorCamera>(std::move(config));
    } catch (const std::exception& err) {
        e.director_failed = true;
        GST_ELEMENT_ERROR(
            self, RESOURCE, SETTINGS,
            ("Cannot use the director camera at \"%s\".", gc::headctl::redact_uri(settings.director).c_str()),
            ("%s", err.what()));
        return false;
    }
    return true;
}

// A `director` element message: what the director did, so that an application (or the demo)
// sees it frame a target, go home, and pause after someone else moved it.
void post_director(GstHandTracker* self, const FrameResult& r, gc::headctl::DirectorEvent event,
                   const std::optional<HeadPose>& aim)
{
    const std::string name(gc::headctl::to_string(event));
    GstStructure* s = gst_structure_new("director", "event", G_TYPE_STRING, name.c_str(), "frame", G_TYPE_UINT64,
                                        guint64(std::max<std::int64_t>(r.frame, 0)), nullptr);
    if (event == gc::headctl::DirectorEvent::Frame && aim)
        gst_structure_set(s, "pan-deg", G_TYPE_DOUBLE, aim->pan_deg, "tilt-deg", G_TYPE_DOUBLE, aim->tilt_deg, "zoom",
                          G_TYPE_DOUBLE, aim->zoom, nullptr);
    GST_INFO_OBJECT(self, "frame %" G_GINT64_FORMAT ": director %s", r.frame, name.c_str());
    gst_element_post_message(GST_ELEMENT(self), gst_message_new_element(GST_OBJECT(self), s));
}

}  // namespace

bool prepare_director(GstHandTracker* self, const TrackerSettings& settings)
{
    TrackerState& e = *self->state;
    e.director.reset();
    e.director_failed = false;
    e.director_token.clear();
    if (settings.director.empty()) return true;
    if (!read_head_token(GST_ELEMENT(self), settings.director_token_file, e.director_token)) return false;
    try {
        // The backend reads its query parameters (zoom_max, speeds, ...) when it is made.
        (void)gc::headctl::make_backend(gc::headctl::parse_head_uri(settings.director), e.director_token);
    } catch (const std::exception& err) {
        GST_ELEMENT_ERROR(self, RESOURCE, SETTINGS,
                          ("Invalid director URI \"%s\".", gc::headctl::redact_uri(settings.director).c_str()),
                          ("%s", err.what()));
        return false;
    }
    return true;
}

void direct_camera(GstHandTracker* self, const TrackerSettings& settings, const FrameResult& result)
{
    if (settings.director.empty() || !ensure_director(self, settings)) return;
    TrackerState& e = *self->state;
    e.director->set_region(settings.target_region_mm);
    e.director->set_manual_pause(settings.manual_pause_s);
    if (const auto event = e.director->show(e.stream.target)) post_director(self, result, *event, e.director->aim());
}

}  // namespace gc::gst
