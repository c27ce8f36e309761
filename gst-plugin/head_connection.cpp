#include "head_connection.hpp"

#include "headctl/uri.hpp"

#include <chrono>
#include <memory>
#include <mutex>

GST_DEBUG_CATEGORY_STATIC(gesturecam_head_debug);
#define GST_CAT_DEFAULT gesturecam_head_debug

namespace gc::gst {

namespace {

void init_head_debug()
{
    static const bool done = [] {
        GST_DEBUG_CATEGORY_INIT(gesturecam_head_debug, "gesturecam-head", 0,
                                "head link: connection, disconnection, commands");
        return true;
    }();
    (void)done;
}

}  // namespace

std::function<headctl::Timestamp()> element_clock(GstElement* element)
{
    return [element] {
        if (GstClock* clock = gst_element_get_clock(element)) {
            const GstClockTime now = gst_clock_get_time(clock);
            gst_object_unref(clock);
            if (GST_CLOCK_TIME_IS_VALID(now)) return headctl::Timestamp(gint64(now));
        }
        return std::chrono::duration_cast<headctl::Timestamp>(std::chrono::steady_clock::now().time_since_epoch());
    };
}

headctl::Timestamp capture_time(GstElement* element, GstClockTime running_time)
{
    const GstClockTime base = gst_element_get_base_time(element);
    GstClock* clock = gst_element_get_clock(element);
    const bool known = clock && GST_CLOCK_TIME_IS_VALID(running_time) && GST_CLOCK_TIME_IS_VALID(base);
    if (clock) gst_object_unref(clock);
    if (known) return headctl::Timestamp(gint64(base + running_time));
    return element_clock(element)();
}

namespace {

// What has been reported, so an outage gives one warning however often the client retries.
struct ReportedState {
    std::mutex mutex;
    bool connected = false;
    bool warned = false;
};

}  // namespace

std::function<void(headctl::ConnectionState, const std::string&)> connection_reporter(GstElement* element,
                                                                                      const std::string& uri)
{
    init_head_debug();
    auto reported = std::make_shared<ReportedState>();
    return
        [element, uri = headctl::redact_uri(uri), reported](headctl::ConnectionState state, const std::string& error) {
            GST_INFO_OBJECT(element, "head %s %s%s%s", uri.c_str(), std::string(headctl::to_string(state)).c_str(),
                            error.empty() ? "" : ": ", error.c_str());
            bool post_change = false, warn = false, back = false;
            {
                std::lock_guard lock(reported->mutex);
                if (state == headctl::ConnectionState::Connected) {
                    post_change = !reported->connected;
                    back = reported->warned;
                    reported->connected = true;
                    reported->warned = false;
                } else if (state == headctl::ConnectionState::Disconnected) {
                    post_change = reported->connected;
                    warn = !reported->warned;
                    reported->connected = false;
                    reported->warned = true;
                }
            }
            if (post_change || warn) {
                GstStructure* s = gst_structure_new("head-connection", "uri", G_TYPE_STRING, uri.c_str(), "state",
                                                    G_TYPE_STRING, std::string(headctl::to_string(state)).c_str(),
                                                    "error", G_TYPE_STRING, error.c_str(), nullptr);
                gst_element_post_message(element, gst_message_new_element(GST_OBJECT(element), s));
            }
            if (warn)
                GST_ELEMENT_WARNING(element, RESOURCE, OPEN_READ_WRITE,
                                    ("Head at %s not connected; retrying in the background.", uri.c_str()),
                                    ("%s", error.empty() ? "connection closed" : error.c_str()));
            if (back)
                GST_ELEMENT_INFO(element, RESOURCE, OPEN_READ_WRITE, ("Head at %s connected again.", uri.c_str()),
                                 (nullptr));
        };
}

std::function<void(headctl::SteeringEvent, const std::string&)> steering_reporter(GstElement* element)
{
    init_head_debug();
    return [element](headctl::SteeringEvent event, const std::string& detail) {
        const std::string name(headctl::to_string(event));
        GST_INFO_OBJECT(element, "steering %s: %s", name.c_str(), detail.c_str());
        GstStructure* s = gst_structure_new("head-steering", "event", G_TYPE_STRING, name.c_str(), "detail",
                                            G_TYPE_STRING, detail.c_str(), nullptr);
        gst_element_post_message(element, gst_message_new_element(GST_OBJECT(element), s));
    };
}

std::function<void(const headctl::HeadCommand&)> command_logger(GstElement* element)
{
    init_head_debug();
    return [element](const headctl::HeadCommand& command) {
        GST_DEBUG_OBJECT(element, "head command: %s", headctl::describe(command).c_str());
    };
}

}  // namespace gc::gst
