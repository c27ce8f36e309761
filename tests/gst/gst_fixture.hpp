// Shared by the element tests: GStreamer initialisation, running a pipeline to its end
// while collecting element messages, and reading frames back from appsink.
#pragma once

#include <gst/app/gstappsink.h>
#include <gst/gst.h>
#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace gc::test {

// gst_init once; the plugin comes from GST_PLUGIN_PATH (set by meson to its build dir).
inline void init_gstreamer()
{
    static const bool done = [] {
        gst_init(nullptr, nullptr);
        return true;
    }();
    (void)done;
}

struct GstUnref {
    void operator()(gpointer object) const { gst_object_unref(object); }
};
struct StructureFree {
    void operator()(GstStructure* s) const { gst_structure_free(s); }
};
struct SampleUnref {
    void operator()(GstSample* s) const { gst_sample_unref(s); }
};
using ElementPtr = std::unique_ptr<GstElement, GstUnref>;
using StructurePtr = std::unique_ptr<GstStructure, StructureFree>;
using SamplePtr = std::unique_ptr<GstSample, SampleUnref>;

// What a pipeline run left on the bus.
struct RunResult {
    bool eos = false;
    std::string error;                   // the first error's message, empty if none
    std::vector<StructurePtr> messages;  // element messages, in posting order
    std::vector<std::string> sources;    // the name of each message's element
    std::vector<double> received_s;      // when each was read, seconds after PLAYING
    std::vector<std::string> warnings;   // "element: message" of each warning
    std::vector<double> warnings_s;      // when each warning was read

    std::vector<const GstStructure*> named(const char* name, const char* source = nullptr) const
    {
        std::vector<const GstStructure*> out;
        for (size_t i = 0; i < messages.size(); ++i)
            if (gst_structure_has_name(messages[i].get(), name) && (!source || sources[i] == source))
                out.push_back(messages[i].get());
        return out;
    }
};

// The lines of a text file (a JSON-lines output), without their newlines.
inline std::vector<std::string> read_lines(const std::string& path)
{
    std::vector<std::string> lines;
    std::ifstream in(path);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

inline ElementPtr parse_pipeline(const std::string& description)
{
    GError* error = nullptr;
    GstElement* pipeline = gst_parse_launch(description.c_str(), &error);
    if (error) {
        ADD_FAILURE() << "cannot parse '" << description << "': " << error->message;
        g_error_free(error);
        if (pipeline) gst_object_unref(pipeline);
        return nullptr;
    }
    return ElementPtr(pipeline);
}

// Plays `pipeline` until EOS or an error (or the timeout), collecting element messages,
// calls `at_end` (to drain appsinks) and sets it to NULL.
inline RunResult run_pipeline(GstElement* pipeline, GstClockTime timeout = 60 * GST_SECOND,
                              const std::function<void()>& at_end = {})
{
    RunResult result;
    GstBus* bus = gst_element_get_bus(pipeline);
    GstClockTime deadline = gst_util_get_timestamp() + timeout;
    const GstClockTime started_at = gst_util_get_timestamp();
    const bool started = gst_element_set_state(pipeline, GST_STATE_PLAYING) != GST_STATE_CHANGE_FAILURE;
    if (!started)  // the reason is on the bus already
        deadline = gst_util_get_timestamp() + 2 * GST_SECOND;
    for (bool stop = false; !stop;) {
        const GstClockTime now = gst_util_get_timestamp();
        if (now >= deadline) break;
        GstMessage* msg = gst_bus_timed_pop_filtered(
            bus, deadline - now,
            GstMessageType(GST_MESSAGE_EOS | GST_MESSAGE_ERROR | GST_MESSAGE_ELEMENT | GST_MESSAGE_WARNING));
        if (!msg) continue;
        const double received = double(gst_util_get_timestamp() - started_at) / GST_SECOND;
        switch (GST_MESSAGE_TYPE(msg)) {
        case GST_MESSAGE_EOS:
            result.eos = true;
            stop = true;
            break;
        case GST_MESSAGE_ERROR: {
            GError* err = nullptr;
            gchar* debug = nullptr;
            gst_message_parse_error(msg, &err, &debug);
            result.error = err->message;
            g_error_free(err);
            g_free(debug);
            stop = true;
            break;
        }
        case GST_MESSAGE_WARNING: {
            GError* err = nullptr;
            gst_message_parse_warning(msg, &err, nullptr);
            result.warnings.push_back(std::string(GST_OBJECT_NAME(GST_MESSAGE_SRC(msg))) + ": " + err->message);
            result.warnings_s.push_back(received);
            g_error_free(err);
            break;
        }
        default:
            if (const GstStructure* s = gst_message_get_structure(msg)) {
                result.messages.emplace_back(gst_structure_copy(s));
                result.sources.emplace_back(GST_OBJECT_NAME(GST_MESSAGE_SRC(msg)));
                result.received_s.push_back(received);
            }
            break;
        }
        gst_message_unref(msg);
    }
    if (result.error.empty() && !result.eos) result.error = started ? "timeout" : "state change to PLAYING failed";
    if (at_end) at_end();
    gst_element_set_state(pipeline, GST_STATE_NULL);
    gst_object_unref(bus);
    return result;
}

inline RunResult run_pipeline(const std::string& description, GstClockTime timeout = 60 * GST_SECOND)
{
    ElementPtr pipeline = parse_pipeline(description);
    if (!pipeline) {
        RunResult failed;
        failed.error = "parse failed";
        return failed;
    }
    return run_pipeline(pipeline.get(), timeout);
}

// Every sample an appsink still holds.
inline std::vector<SamplePtr> drain(GstElement* pipeline, const char* appsink_name)
{
    std::vector<SamplePtr> out;
    GstElement* sink = gst_bin_get_by_name(GST_BIN(pipeline), appsink_name);
    if (!sink) {
        ADD_FAILURE() << "no element " << appsink_name;
        return out;
    }
    while (GstSample* sample = gst_app_sink_try_pull_sample(GST_APP_SINK(sink), 0)) out.emplace_back(sample);
    gst_object_unref(sink);
    return out;
}

// Calls `callback` with `data` for every buffer through `pad` of the element `element`.
inline void probe_buffers(GstElement* pipeline, const char* element, const char* pad, GstPadProbeCallback callback,
                          gpointer data)
{
    GstElement* e = gst_bin_get_by_name(GST_BIN(pipeline), element);
    ASSERT_NE(e, nullptr) << "no element " << element;
    GstPad* p = gst_element_get_static_pad(e, pad);
    ASSERT_NE(p, nullptr) << "no pad " << element << "." << pad;
    gst_pad_add_probe(p, GST_PAD_PROBE_TYPE_BUFFER, callback, data, nullptr);
    gst_object_unref(p);
    gst_object_unref(e);
}

inline double get_double(const GstStructure* s, const char* field)
{
    double v = 0.0;
    EXPECT_TRUE(gst_structure_get_double(s, field, &v)) << "no double field " << field;
    return v;
}

inline const GstStructure* get_child(const GstStructure* s, const char* field)
{
    const GValue* v = gst_structure_get_value(s, field);
    if (!v || !GST_VALUE_HOLDS_STRUCTURE(v)) return nullptr;
    return gst_value_get_structure(v);
}

inline std::string build_dir() { return g_getenv("GESTURECAM_BUILD_ROOT") ? g_getenv("GESTURECAM_BUILD_ROOT") : "."; }

}  // namespace gc::test
